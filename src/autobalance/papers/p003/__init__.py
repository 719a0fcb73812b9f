"""Reproduction of seed 003 (Drach, Dykha, Matiukh, Dykha 2025): Leblanc balancer on a vertical rotor."""
