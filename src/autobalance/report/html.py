"""The reproduction report as one HTML page (figures are PNG files beside it, linked relatively).

The page has no external resources. A small script marks any figure that fails to load (a red
note in the page, and the counts in ``#image-check``), so a broken image is visible to a reader
and testable in a headless browser.
"""
from __future__ import annotations

from html import escape

from .registry import PAPERS
from .summary import counts as _counts
from .summary import summary_lines

__all__ = ["fmt_value", "render_html"]

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:0 auto;max-width:1200px;
padding:0 1.2em 3em;color:#1b1b1b;line-height:1.4}
h1{margin-bottom:.2em}h2{border-bottom:2px solid #ccc;margin-top:2em}
h3{margin-bottom:.3em}.meta{color:#555;font-size:.9em}
table{border-collapse:collapse;margin:.6em 0;font-size:.88em}
th,td{border:1px solid #ccc;padding:3px 7px;vertical-align:top;text-align:left}
th{background:#f2f2f2}td.num{text-align:right}
tr.pass td.st{background:#dff3df}tr.miss td.st{background:#fbdada}
tr.not-computed td.st{background:#fff2c6}
.badge{display:inline-block;padding:0 .45em;border-radius:.6em;font-size:.8em;margin-left:.3em}
.b-pass{background:#dff3df}.b-miss{background:#fbdada}.b-nc{background:#fff2c6}
.b-err{background:#d33;color:#fff}
figure{margin:.6em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.85em;color:#444}
.error{background:#fbdada;border:1px solid #d33;padding:.4em .8em}
.notes{background:#f7f7f7;padding:.4em .8em;border-left:3px solid #bbb;font-size:.9em}
.broken{color:#d33;font-weight:bold}
nav ul{columns:2;font-size:.9em}
"""

SCRIPT = """
(function(){
  function check(){
    var imgs=document.querySelectorAll('img.fig'), broken=0;
    imgs.forEach(function(img){
      if(!(img.complete && img.naturalWidth>0)){
        broken++;
        var p=document.createElement('p');p.className='broken';
        p.textContent='figure missing: '+img.getAttribute('src');
        img.parentNode.insertBefore(p,img);
      }
    });
    var el=document.getElementById('image-check');
    el.setAttribute('data-total',imgs.length);el.setAttribute('data-broken',broken);
    el.setAttribute('data-done','1');
    el.textContent=broken? broken+' of '+imgs.length+' figures failed to load':
                           'all '+imgs.length+' figures loaded';
  }
  if(document.readyState==='complete'){check();}else{window.addEventListener('load',check);}
})();
"""


def fmt_value(v: object) -> str:
    """A published/computed/tolerance value as text."""
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, (list, tuple)):
        return ", ".join(fmt_value(x) for x in v) if v else "none"
    return str(v)


def _badges(c: dict) -> str:
    out = [f'<span class="badge b-pass">{c["pass"]} pass</span>']
    if c["miss"]:
        out.append(f'<span class="badge b-miss">{c["miss"]} miss</span>')
    if c["not computed"]:
        out.append(f'<span class="badge b-nc">{c["not computed"]} not computed</span>')
    if c["unreported"] or c["errors"]:
        out.append(f'<span class="badge b-err">{c["unreported"]} unreported, '
                   f'{c["errors"]} errors</span>')
    return "".join(out)


def _summary(report: dict) -> str:
    s = report["summary"]
    head = ("<tr><th>paper</th><th>targets</th><th>published quantities</th><th>pass</th>"
            "<th>miss</th><th>not computed</th><th>unreported</th><th>errors</th></tr>")
    body = []
    for paper, c in summary_lines(s):
        name = escape(PAPERS[paper][0]) if paper in PAPERS else "<b>total</b>"
        attrs = " ".join(f'data-{k.replace(" ", "-")}="{v}"' for k, v in c.items())
        body.append(f'<tr id="summary-{paper}" {attrs}><td>{paper if paper != "total" else ""} '
                    f'{name}</td><td class="num">{c["targets"]}</td><td class="num">'
                    f'{c["published"]}</td><td class="num">{c["pass"]}</td><td class="num">'
                    f'{c["miss"]}</td><td class="num">{c["not computed"]}</td><td class="num">'
                    f'{c["unreported"]}</td><td class="num">{c["errors"]}</td></tr>')
    return f'<table id="summary">{head}{"".join(body)}</table>'


def _rows_table(rec: dict) -> str:
    if not rec["rows"]:
        return ""
    head = ("<tr><th>quantity</th><th>published</th><th>computed</th><th>tolerance</th>"
            "<th>result</th><th>note</th></tr>")
    body = []
    for r in rec["rows"]:
        st = r["status"]
        body.append(f'<tr class="{st.replace(" ", "-")}" data-key="{escape(str(r.get("key")))}">'
                    f'<td>{escape(str(r["quantity"]))}</td>'
                    f'<td>{escape(fmt_value(r["published"]))}</td>'
                    f'<td>{escape(fmt_value(r["computed"]))}</td>'
                    f'<td>{escape(fmt_value(r["tolerance"]))}</td>'
                    f'<td class="st">{st}</td><td>{escape(str(r.get("note", "")))}</td></tr>')
    return f'<table class="rows">{head}{"".join(body)}</table>'


def _target(rec: dict, variant: str) -> str:
    c = _counts([rec])
    parts = [f'<section class="target" id="t-{rec["id"]}" data-target="{rec["id"]}" '
             f'data-status="{escape(rec["status"])}">',
             f'<h3>{escape(", ".join(rec["items"]))}: {escape(rec["title"])}'
             f'{_badges(c) if rec["claims"] or rec["rows"] else ""}</h3>',
             f'<p class="meta">target <code>{rec["id"]}</code>']
    if rec["status"] == "nothing to compute":
        parts.append(" &middot; nothing to compute</p>")
    else:
        parts.append(f' &middot; {rec["wall_time_s"]:.1f} s &middot; {variant}')
        if rec["run_notes"]:
            parts.append(f' &middot; {escape(rec["run_notes"])}')
        if variant == "quick" and rec["quick"]:
            parts.append(f'<br>--quick: {escape(rec["quick"])}')
        parts.append("</p>")
    if rec["error"]:
        parts.append(f'<p class="error">error: {escape(rec["error"])}</p>')
    for f in rec["figures"]:
        svg = f[:-4] + ".svg"
        parts.append(f'<figure><img class="fig" src="{escape(f)}" alt="{escape(f)}">'
                     f'<figcaption>{escape(f)} (<a href="{escape(svg)}">SVG</a>)</figcaption>'
                     f'</figure>')
    parts.append(_rows_table(rec))
    if rec["unreported"]:
        parts.append('<p class="error">published numbers without a row (unreported): '
                     f'{escape(", ".join(rec["unreported"]))}</p>')
    if rec["notes"]:
        parts.append(f'<div class="notes">{escape(rec["notes"])}</div>')
    if rec["data"]:
        links = ", ".join(f'<a href="{escape(d)}">{escape(d)}</a>' for d in rec["data"])
        parts.append(f'<p class="meta">data: {links}</p>')
    parts.append("</section>")
    return "".join(parts)


def render_html(report: dict) -> str:
    """The self-contained HTML page of a report (the runner's dict): summary, one section per
    target with its rows, figures and data files.

    Parameters
    ----------
    report : dict
        :func:`autobalance.report.runner.run_targets`' result.
    """
    recs = report["targets"]
    t = report["summary"]["total"]
    nav, body = [], []
    for paper in PAPERS:
        mine = [r for r in recs if r["paper"] == paper]
        if not mine:
            continue
        title, seed = PAPERS[paper]
        body.append(f'<h2 id="paper-{paper}">{paper}: {escape(title)}</h2>'
                    f'<p class="meta">seed file <code>{seed}</code></p>')
        for rec in mine:
            nav.append(f'<li><a href="#t-{rec["id"]}">{paper} {escape(", ".join(rec["items"]))}'
                       f'</a></li>')
            body.append(_target(rec, report["variant"]))
    cmd = f"autobalance reproduce all --{report['variant']} --out {escape(str(report['out']))}"
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>autobalance reproduction report ({report['variant']})</title>
<style>{CSS}</style></head><body>
<h1>autobalance: the seed papers reproduced</h1>
<p class="meta">autobalance {escape(report['autobalance_version'])} &middot; variant
<b>{report['variant']}</b> &middot; {report['wall_time_s']:.0f} s &middot; <code>{cmd}</code></p>
<p id="headline">{t['pass']} of {t['published']} published quantities reproduced within tolerance;
{t['miss']} missed (each with its reason), {t['not computed']} not computed in this variant,
{t['unreported']} unreported, {t['errors']} targets failed.</p>
{_summary(report)}
<p class="meta">A <b>miss</b> is a published number we compute but do not reproduce within the
stated tolerance; the note says why. <b>Not computed</b>: the case does not run in this variant
(run with <code>--full</code>). Figures are ours; the papers' figures are not reproduced here.
<span id="image-check" data-done="0"></span></p>
<nav><ul>{''.join(nav)}</ul></nav>
{''.join(body)}
<script>{SCRIPT}</script>
</body></html>
"""
