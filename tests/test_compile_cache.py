"""The compiled cache of core/ follows every core source (docs/numerics/index.md, "Compilation cache"):
numba alone keeps a kernel's machine code while a kernel it calls in another file changes."""
from autobalance.core.jit import _drop_stale_cache


def test_a_change_in_any_core_source_drops_every_cached_kernel(tmp_path):
    (tmp_path / "rhs.py").write_text("x = 1\n")
    (tmp_path / "batch.py").write_text("y = 2\n")
    cache = tmp_path / "__pycache__"
    cache.mkdir()

    def compiled():
        for name in ("batch.integrate_batch-12.py311.nbi", "batch.integrate_batch-12.py311.1.nbc"):
            (cache / name).write_bytes(b"machine code")

    compiled()
    assert _drop_stale_cache(tmp_path)                       # no stamp yet: start clean
    assert not list(cache.glob("*.nb?"))
    compiled()
    assert not _drop_stale_cache(tmp_path)                   # sources unchanged: cache kept
    assert len(list(cache.glob("*.nb?"))) == 2
    (tmp_path / "rhs.py").write_text("x = 3\n")              # a callee changes in another file
    assert _drop_stale_cache(tmp_path)
    assert not list(cache.glob("*.nb?"))
