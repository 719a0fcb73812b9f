"""The reproduction report (issue 7): registry coverage of every seed table/figure, the runner's
bookkeeping (no silent skips), the real `autobalance reproduce all --quick` run once per session,
its HTML page in a real headless Chromium, and docs/VALIDATION.md generated from the same rows."""
import json
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import pytest

from autobalance.report import registry
from autobalance.report.html import render_html
from autobalance.report.markdown import render_markdown
from autobalance.report.runner import run_targets, summary_lines, write_report
from autobalance.report.target import Context, Outcome, Target, claims, not_computed, row

ROOT = Path(__file__).resolve().parents[1]
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


# -- the contract -----------------------------------------------------------------------------
def test_claims_walk_every_leaf_but_descriptions():
    pub = {"a": 1.0, "b": {"c": (1, 2), "d": {"e": "text"}}, "source": "x", "_note": "y"}
    t = Target("000-x", "000", ("Fig. 1",), "t", published=pub, prefix="p")
    assert claims(t) == ["p/a", "p/b/c", "p/b/d/e"]
    assert claims(Target("000-y", "000", ("Fig. 2",), "t")) == []


def _fake(rows_for, tid="004-fake", items=("Fig. 99",), raises=None):
    pub = {"x": 1.0, "y": 2.0, "source": "s"}

    def run(ctx):
        if raises:
            raise raises
        return Outcome(rows=rows_for(tid), figures={}, data=None, notes="fake")

    return Target(tid, "004", items, "fake", run, pub)


def test_runner_flags_unreported_unclaimed_and_errors(tmp_path):
    good = _fake(lambda p: [row(f"{p}/x", "x", 1.0, 1.02, 0.05, True),
                            not_computed(f"{p}/y", "y", 2.0)], tid="004-good")
    silent = _fake(lambda p: [row(f"{p}/x", "x", 1.0, 1.5, 0.05, False)], tid="004-silent")
    extra = _fake(lambda p: [row(f"{p}/x", "x", 1.0, 1.0, 0.05, True),
                             row(f"{p}/y", "y", 2.0, 2.0, 0.05, True),
                             row(f"{p}/z", "z", 3.0, 3.0, 0.05, True)], tid="004-extra")
    boom = _fake(None, tid="004-boom", raises=RuntimeError("kaboom\nsecond line"))
    rep = run_targets([good, silent, extra, boom], Context(out=tmp_path))
    by = {r["id"]: r for r in rep["targets"]}
    assert [r["status"] for r in by["004-good"]["rows"]] == ["pass", "not computed"]
    assert by["004-silent"]["unreported"] == ["004-silent/y"]
    assert by["004-extra"]["status"] == "error" and "004-extra/z" in by["004-extra"]["error"]
    assert by["004-boom"]["status"] == "error" and by["004-boom"]["error"] == "RuntimeError: kaboom second line"
    assert by["004-boom"]["unreported"] == ["004-boom/x", "004-boom/y"]
    t = rep["summary"]["total"]
    assert (t["published"], t["pass"], t["miss"], t["not computed"], t["unreported"], t["errors"]) \
        == (8, 3, 1, 1, 3, 2)
    paths = write_report(rep, tmp_path)
    html = Path(paths["html"]).read_text()
    assert "unreported" in html and "kaboom" in html
    md = Path(paths["markdown"]).read_text()
    assert "**Unreported:** 004-silent/y" in md and "**Error:** RuntimeError" in md


def test_registry_ids_and_seed_coverage():
    targets = registry.all_targets()
    registry.check_ids(targets)
    items = registry.seed_items()
    assert set(items) == set(registry.PAPERS)
    for paper, cov in registry.coverage(targets).items():
        assert cov == {"missing": [], "twice": [], "unknown": []}, paper
    # 004: every figure and table of the paper (Fig. 1-16, Table 1-4)
    assert len(items["004"]) == 20
    for t in targets:
        if t.run is None:
            assert t.notes and not claims(t), t.id      # says why nothing is computed
        else:
            assert claims(t), t.id                       # a computed target claims numbers


def test_select_names_groups_and_errors():
    from autobalance.config import ConfigError

    ids = [t.id for t in registry.select(["004"])]
    assert ids and all(i.startswith("004-") for i in ids)
    liquid = {t.paper for t in registry.select(["liquid"])}
    assert liquid == {"001", "003"}
    assert [t.id for t in registry.select(["004-fig4", "004-fig4"])] == ["004-fig4"]
    with pytest.raises(ConfigError, match="TARGET = 'nope'"):
        registry.select(["nope"])
    # the tsr-* names select the 004 targets; an alias and its id count once
    assert [t.id for t in registry.select(["tsr-mc", "004-fig5-6-table2"])] == ["004-fig5-6-table2"]
    assert [t.id for t in registry.select(["tsr-plateau", "tsr-single"])] == ["004-fig4",
                                                                               "004-fig14-16"]


def test_check_ids_rejects_alias_clashes():
    from dataclasses import replace

    targets = registry.all_targets()
    mc = next(t for t in targets if t.id == "004-fig5-6-table2")
    for bad in ("004-fig4", "tsr-single", "004", "all", "Bad Name"):
        with pytest.raises(ValueError, match="bad or duplicate target name"):
            registry.check_ids([*targets, replace(mc, id="004-x", aliases=(bad,))])


# -- the real quick run, once per session -----------------------------------------------------
@pytest.fixture(scope="session")
def quick_report(tmp_path_factory):
    """`autobalance reproduce all --quick --json` as a user runs it (a real process)."""
    out = tmp_path_factory.mktemp("report")
    exe = Path(shutil.which("autobalance") or ROOT / ".venv" / "bin" / "autobalance")
    p = subprocess.run([str(exe), "reproduce", "all", "--quick", "--out", str(out), "--json"],
                       capture_output=True, text=True, timeout=900)
    assert p.returncode == 0, p.stderr[-3000:]
    return json.loads(p.stdout), out


def test_quick_report_complete_no_silent_skips(quick_report):
    rep, out = quick_report
    assert rep["variant"] == "quick"
    ids = [t["id"] for t in rep["targets"]]
    assert ids == [t.id for t in registry.all_targets()]
    for tg in rep["targets"]:
        assert tg["status"] in ("ran", "nothing to compute"), (tg["id"], tg["error"])
        keys = [r["key"] for r in tg["rows"]]
        assert sorted(keys) == sorted(tg["claims"]), tg["id"]       # every claim compared once
        assert not tg["unreported"] and not tg["unclaimed"]
        for r in tg["rows"]:
            assert r["status"] in ("pass", "miss", "not computed")
            if r["status"] == "miss":
                assert r["note"], (tg["id"], r["quantity"])          # a miss says why
        for f in tg["figures"]:
            assert (out / f).stat().st_size > 2000 and (out / f).with_suffix(".svg").exists()
        for d in tg["data"]:
            assert (out / d).stat().st_size > 0
        if tg["status"] == "ran" and any(i.startswith("Fig.") for i in tg["items"]):
            assert tg["figures"], f"{tg['id']} reproduces a figure but draws none"
    t = rep["summary"]["total"]
    assert t["unreported"] == 0 and t["errors"] == 0
    assert t["pass"] + t["miss"] + t["not computed"] == t["published"]
    for name in ("report.html", "report.json", "VALIDATION.md"):
        assert (out / name).exists()
    assert json.loads((out / "report.json").read_text())["summary"] == rep["summary"]


class _Dom(HTMLParser):
    """Sections, images and the summary/image-check attributes of the page Chromium rendered."""

    def __init__(self):
        super().__init__()
        self.targets, self.imgs, self.ids = [], [], {}

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "section" and "data-target" in a:
            self.targets.append(a["data-target"])
        if tag == "img":
            self.imgs.append(a.get("src"))
        if "id" in a:
            self.ids[a["id"]] = a


def test_html_report_in_headless_chromium(quick_report, tmp_path):
    """Open out/report.html in Debian's Chromium: every figure loads (checked by the page's own
    script after the load event), every target has its section, the summary matches --json."""
    if CHROMIUM is None:
        pytest.fail("chromium not found: `make test` installs Debian's chromium "
                    "(apt-get install chromium)")
    rep, out = quick_report
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
           "--no-first-run", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", f"--user-data-dir={tmp_path / 'profile'}",
           "--virtual-time-budget=15000", "--dump-dom", (out / "report.html").as_uri()]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=180)
    assert p.returncode == 0, p.stderr[-2000:]
    dom = _Dom()
    dom.feed(p.stdout)
    check = dom.ids["image-check"]
    n_fig = sum(len(t["figures"]) for t in rep["targets"])
    assert check["data-done"] == "1"
    assert int(check["data-total"]) == n_fig == len(dom.imgs) > 10
    assert int(check["data-broken"]) == 0, re.findall(r"figure missing: [^<]+", p.stdout)
    assert dom.targets == [t["id"] for t in rep["targets"]]
    for paper, c in summary_lines(rep["summary"]):
        attrs = dom.ids[f"summary-{paper}"]
        for k, v in c.items():
            assert int(attrs[f"data-{k.replace(' ', '-')}"]) == v, (paper, k)


def test_broken_image_is_detected_by_the_browser_check(quick_report, tmp_path):
    """The same check fails when a figure file is missing (the check can fail)."""
    if CHROMIUM is None:
        pytest.fail("chromium not found")
    rep, _ = quick_report
    bad = json.loads(json.dumps(rep))
    bad["targets"] = [t for t in bad["targets"] if t["figures"]][:1]
    bad["targets"][0]["figures"] = ["figures/does-not-exist.png"]
    page = tmp_path / "bad.html"
    page.write_text(render_html(bad))
    p = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                        "--no-first-run", "--disable-background-networking",
                        f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=5000",
                        "--dump-dom", page.as_uri()], capture_output=True, text=True, timeout=120)
    dom = _Dom()
    dom.feed(p.stdout)
    assert dom.ids["image-check"]["data-broken"] == "1"
    assert "figure missing: figures/does-not-exist.png" in p.stdout


def test_validation_md_is_generated_from_the_same_rows(quick_report):
    """docs/VALIDATION.md (committed) = the markdown of a quick run: same rows and statuses."""
    rep, out = quick_report
    assert (out / "VALIDATION.md").read_text() == render_markdown(rep)
    committed = (ROOT / "docs" / "VALIDATION.md").read_text()

    def table_rows(text):
        # quantity, published, result of every table row (computed values may differ in the
        # last printed digit between machines; the verdicts may not)
        rows = []
        for line in text.splitlines():
            cells = [c.strip() for c in line.strip().strip("|").split(" | ")]
            if line.startswith("| ") and len(cells) == 6 and cells[0] != "quantity":
                rows.append((cells[0], cells[1], cells[4]))
        return rows

    assert table_rows(committed) == table_rows(render_markdown(rep))
