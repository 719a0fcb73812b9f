"""Reproduction of seed 000 (Majewski et al.): self-balancing of a washing machine with balls."""
