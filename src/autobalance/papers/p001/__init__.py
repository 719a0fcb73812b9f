"""Reproduction of seed 001 (Drach 2018): the fluid balancer, influence of the liquid's viscosity."""
