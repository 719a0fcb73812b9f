"""Reproduction studies of the seed papers: ``compute`` (data), ``PUBLISHED`` and ``compare`` (rows)."""
from . import washer_000

__all__ = ["washer_000"]
