"""The report of a reproduction: claims with the source's words, the program's measurement and
a verdict, written as Markdown (report.md, charts beside it), self-contained HTML
(report.html, charts embedded) and claims.csv."""
from dataclasses import dataclass, field
import base64
import csv
import html
import os
import platform
import subprocess

from . import departures
from .verdicts import AGREES, DISAGREES, UNRESOLVED


@dataclass
class Claim:
    id: str                  # short slug, unique in a report
    topic: str               # group heading
    source: str              # what the source says (quoted)
    where: str               # figure, equation, section
    measured: str            # what the program measured, with its 95 % interval
    verdict: str             # AGREES, DISAGREES, UNRESOLVED
    reason: str              # the numbers that decided it
    resolve: str = ""        # when not resolved: the budget that would resolve it
    chart: str = ""          # PNG path relative to the report folder
    values: dict = field(default_factory=dict)  # numbers for claims.csv
    power: str = ""          # the test's power against the source's alternative at this length
    null: str = ""           # the test's null hypothesis
    alternative: str = ""    # the alternative the source names or shows, with its size
    power_at: object = None  # k ↦ the power at k times the run's length (not written)


def test_of(v):
    """the null, alternative and power of a verdicts.Verdict, as Claim keywords"""
    p = v.power
    return dict(power=f"{p:.2f}" if p is not None and p == p else "", null=v.null,
                alternative=v.alternative, power_at=v.power_at)


BADGE = {AGREES: "#1a7f37", DISAGREES: "#c62828", UNRESOLVED: "#8a6d00"}


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"


def program_version(gransim):
    try:
        out = subprocess.run([gransim, "--version"], capture_output=True, text=True, timeout=10)
        return out.stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def _counts(claims):
    n = {AGREES: 0, DISAGREES: 0, UNRESOLVED: 0}
    for c in claims:
        n[c.verdict] += 1
    return n


def write_csv(path, claims):
    keys = sorted({k for c in claims for k in c.values})
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "topic", "where", "verdict", "power", "measured", "reason", "null",
                    "alternative"] + keys)
        for c in claims:
            w.writerow([c.id, c.topic, c.where, c.verdict, c.power, c.measured, c.reason, c.null,
                        c.alternative] + [c.values.get(k, "") for k in keys])


def _cell(t):
    return t.replace("|", "\\|").replace("\n", " ")


def departures_markdown(study, facts=None):
    """the departures table of a report's header, in Markdown"""
    lines = ["## Departures from the source", "", departures.head(study, facts), "",
             "| departure | source printed | program runs | why | effect measured |",
             "|---|---|---|---|---|"]
    for what, printed, runs, why, (text, link), effect in departures.rows(study, facts):
        lines.append(f"| {_cell(what)} | {_cell(printed)} | {_cell(runs)} | {_cell(why)} "
                     f"([{text}]({link})) | {_cell(effect)} |")
    return lines


def write_markdown(path, title, intro, meta, claims, notes, study="", facts=None):
    n = _counts(claims)
    lines = [f"# {title}", "", intro, ""]
    lines += [f"- **{k}**: {v}" for k, v in meta]
    if study:
        lines += [""] + departures_markdown(study, facts)
    lines += ["", "## Verdicts", "",
              f"**Verdicts**: {n[AGREES]} agree, {n[DISAGREES]} disagree, "
              f"{n[UNRESOLVED]} not resolved at this budget.", "",
              "| claim | source says | program measured | verdict | power |",
              "|---|---|---|---|---|"]
    cell = _cell

    for c in claims:
        lines.append(f"| [{c.id}](#{c.id}) | {cell(c.source)} ({cell(c.where)}) | "
                     f"{cell(c.measured)} | **{c.verdict}** | {cell(c.power) or '—'} |")
    topic = None
    for c in claims:
        if c.topic != topic:
            topic = c.topic
            lines += ["", f"## {topic}"]
        lines += ["", f"### {c.id}", "", f"<a id=\"{c.id}\"></a>", "",
                  f"> {c.source}", ">", f"> — {c.where}", "",
                  f"**Measured**: {c.measured}", "", f"**Verdict: {c.verdict}** — {c.reason}"]
        if c.power or c.null:
            lines += ["", f"**Power**: {c.power or '—'} (null: {c.null or '—'}; alternative: "
                      f"{c.alternative or '—'})"]
        if c.resolve:
            lines += ["", f"**To resolve**: {c.resolve}"]
        if c.chart:
            lines += ["", f"![{c.id}]({c.chart})"]
    if notes:
        lines += ["", "## Notes", ""] + [f"- {x}" for x in notes]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def _img(folder, rel):
    p = os.path.join(folder, rel)
    if not rel or not os.path.exists(p):
        return ""
    with open(p, "rb") as f:
        data = base64.b64encode(f.read()).decode()
    return f'<img alt="{html.escape(rel)}" src="data:image/png;base64,{data}">'


def departures_html(study, facts=None):
    """the departures table of a report's header, in HTML"""
    e = html.escape
    out = ["<h2>Departures from the source</h2>", f"<p>{e(departures.head(study, facts))}</p>",
           "<table><tr><th>departure</th><th>source printed</th><th>program runs</th>"
           "<th>why</th><th>effect measured</th></tr>"]
    for what, printed, runs, why, (text, link), effect in departures.rows(study, facts):
        out.append(f"<tr><td>{e(what)}</td><td>{e(printed)}</td><td>{e(runs)}</td>"
                   f'<td>{e(why)} (<a href="{e(link)}">{e(text)}</a>)</td><td>{e(effect)}</td></tr>')
    return out + ["</table>"]


def write_html(path, title, intro, meta, claims, notes, study="", facts=None):
    folder = os.path.dirname(os.path.abspath(path))
    e = html.escape
    n = _counts(claims)
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           f"<title>{e(title)}</title>", "<style>",
           "body{font-family:DejaVu Sans,Arial,sans-serif;max-width:1100px;margin:2em auto;"
           "padding:0 1em;color:#222;line-height:1.45}",
           "table{border-collapse:collapse;width:100%;font-size:0.9em}",
           "td,th{border:1px solid #ccc;padding:4px 6px;vertical-align:top;text-align:left}",
           "th{background:#f0f0f0}", ".badge{color:#fff;border-radius:4px;padding:1px 6px;"
           "white-space:nowrap;font-weight:bold}",
           "blockquote{border-left:4px solid #bbb;margin:0.5em 0;padding:0.2em 0.8em;"
           "color:#444;background:#fafafa}",
           "img{max-width:100%;border:1px solid #ddd;margin-top:0.5em}",
           ".claim{border-top:1px solid #ddd;margin-top:1.5em;padding-top:0.5em}",
           "</style></head><body>", f"<h1>{e(title)}</h1>", f"<p>{e(intro)}</p>", "<ul>"]
    out += [f"<li><b>{e(k)}</b>: {e(str(v))}</li>" for k, v in meta]
    out.append("</ul>")
    if study:
        out += departures_html(study, facts)
    out += ["<h2>Verdicts</h2>", f"<p><b>Verdicts</b>: {n[AGREES]} agree, {n[DISAGREES]} "
            f"disagree, {n[UNRESOLVED]} not resolved at this budget.</p>",
            "<table><tr><th>claim</th><th>source says</th><th>program measured</th>"
            "<th>verdict</th><th>power</th></tr>"]

    def badge(v):
        return f'<span class="badge" style="background:{BADGE[v]}">{e(v)}</span>'

    for c in claims:
        out.append(f'<tr><td><a href="#{e(c.id)}">{e(c.id)}</a></td><td>{e(c.source)} '
                   f"<i>({e(c.where)})</i></td><td>{e(c.measured)}</td><td>{badge(c.verdict)}"
                   f"</td><td>{e(c.power) or '—'}</td></tr>")
    out.append("</table>")
    topic = None
    for c in claims:
        if c.topic != topic:
            topic = c.topic
            out.append(f"<h2>{e(topic)}</h2>")
        out += [f'<div class="claim" id="{e(c.id)}"><h3>{e(c.id)} {badge(c.verdict)}</h3>',
                f"<blockquote>{e(c.source)}<br>— <i>{e(c.where)}</i></blockquote>",
                f"<p><b>Measured</b>: {e(c.measured)}</p>",
                f"<p><b>Verdict</b>: {e(c.reason)}</p>"]
        if c.power or c.null:
            out.append(f"<p><b>Power</b>: {e(c.power or '—')} (null: {e(c.null or '—')}; "
                       f"alternative: {e(c.alternative or '—')})</p>")
        if c.resolve:
            out.append(f"<p><b>To resolve</b>: {e(c.resolve)}</p>")
        out.append(_img(folder, c.chart))
        out.append("</div>")
    if notes:
        out += ["<h2>Notes</h2>", "<ul>"] + [f"<li>{e(x)}</li>" for x in notes] + ["</ul>"]
    out.append("</body></html>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def write_report(folder, title, intro, meta, claims, notes=(), study="", facts=None):
    """study ("tapping", "rfm") puts its departures table in the header; facts (the runs' own
    pile, described.pile) fill its cells with what these runs ran"""
    ids = [c.id for c in claims]
    if len(ids) != len(set(ids)):
        raise ValueError("claim ids repeat: " + ", ".join(ids))
    for c in claims:
        if c.verdict not in BADGE:
            raise ValueError(f"claim {c.id}: verdict {c.verdict!r}")
    write_markdown(os.path.join(folder, "report.md"), title, intro, meta, claims, list(notes),
                   study, facts)
    write_html(os.path.join(folder, "report.html"), title, intro, meta, claims, list(notes),
               study, facts)
    write_csv(os.path.join(folder, "claims.csv"), claims)
