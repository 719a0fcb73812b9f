"""The compiled cache of core/ follows every core source (docs/numerics/index.md, "Compilation cache"):
numba alone keeps a kernel's machine code while a kernel it calls in another file changes."""
from autobalance.core.jit import _drop_stale_cache


def _core(root):
    """A package's core/ with two sources and an empty cache, at root/src/autobalance/core."""
    core = root / "src" / "autobalance" / "core"
    (core / "__pycache__").mkdir(parents=True)
    (core / "rhs.py").write_text("x = 1\n")
    (core / "batch.py").write_text("y = 2\n")
    return core, core / "__pycache__"


def test_a_change_in_any_core_source_drops_every_cached_kernel(tmp_path):
    (tmp_path / "pyproject.toml").write_text("[project]\n")     # a source checkout
    core, cache = _core(tmp_path)

    def compiled():
        for name in ("batch.integrate_batch-12.py311.nbi", "batch.integrate_batch-12.py311.1.nbc"):
            (cache / name).write_bytes(b"machine code")

    compiled()
    assert _drop_stale_cache(core)                           # no stamp yet: start clean
    assert not list(cache.glob("*.nb?"))
    compiled()
    assert not _drop_stale_cache(core)                       # sources unchanged: cache kept
    assert len(list(cache.glob("*.nb?"))) == 2
    (core / "rhs.py").write_text("x = 3\n")                  # a callee changes in another file
    assert _drop_stale_cache(core)
    assert not list(cache.glob("*.nb?"))


def test_an_installed_package_is_left_to_numba(tmp_path):
    """Outside a source checkout (no pyproject.toml above src/autobalance/core: an installed
    release) nothing is deleted or written: numba's own check of each file applies."""
    core, cache = _core(tmp_path / "site-packages")
    (cache / "rhs.rhs-181.py311.1.nbc").write_bytes(b"machine code")
    assert not _drop_stale_cache(core)
    assert [p.name for p in cache.iterdir()] == ["rhs.rhs-181.py311.1.nbc"]
