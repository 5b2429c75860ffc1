"""Writing a study's results: CSV tables, figures, ``summary.json``, a README per study and
``results/index.md``.  Everything here is generated; nothing is read back except the
summaries, to regenerate the index."""
from __future__ import annotations

import json
import math
from pathlib import Path


from ..glossary import describe
from ..provenance import jsonable as _jsonable
from ..provenance import provenance
from .base import StudyResult
from .output import (  # noqa: F401 - prepare_output is part of this module's API
    prepare_output,
    summary_of,
    writable_names,
    write_atomic,
    write_text_atomic,
)
from .spec import describe_schema


def largest_deviation(result: StudyResult) -> str:
    """The comparison with the largest deviation relative to its tolerance, as text."""
    if not result.comparisons:
        return ""

    def badness(c):
        v = abs(c["value"]) if math.isfinite(c["value"]) else math.inf
        return v / c["limit"] if c["limit"] > 0 else (math.inf if v > 0 else 0.0)

    worst = max(result.comparisons, key=badness)
    value = "not found" if not math.isfinite(worst["value"]) else f"{worst['value']:.3g}"
    return f"{worst['what']}: {value} (tolerance {worst['limit']:.3g})"


#: how the internal checks are named wherever they are counted (console, index): they check
#: the computation, not the thing studied, so the words cannot read as "the design passed"
CHECKS = "consistency checks hold"


def summary_line(result: StudyResult, folder: str = "") -> str:
    """What the terminal shows of a finished study: one line of checks, agreement, time and
    folder; a study with a verdict (a design) adds it as a second, last line."""
    n = len(result.checks)
    ok = sum(c["passed"] for c in result.checks)
    agree = result.agreement
    if result.comparisons:
        agree += f" ({largest_deviation(result)})"
    line = (f"{result.study.name}: {ok}/{n} {CHECKS}; agrees with the published "
            f"reference: {agree}; {result.wall_time_s:.1f} s")
    failed = [c["what"] for c in result.checks if not c["passed"]]
    if failed:
        line += f"; FAILED: {failed[0]}" + (f" (+{len(failed) - 1} more)" if len(failed) > 1
                                            else "")
    line += f" -> {folder}" if folder else ""
    return line + (f"\n{result.study.name}: {result.verdict}" if result.verdict else "")


def _reference_names(published) -> list:
    """The reference names a ``published`` entry gives: a table's keys; none for a file of
    published values (a path) or when the study has none."""
    return list(published) if isinstance(published, dict) else []


def _references(result: StudyResult) -> tuple:
    spec = result.study.spec
    refs = set(spec.get("references") or []) | set(_reference_names(spec.get("published")))
    for key in ("rows", "cases"):
        for row in spec.get(key) or []:
            refs |= set(_reference_names(row.get("published")) if isinstance(row, dict)
                        else [])
    refs |= {p["reference"] for p in spec.get("comparisons") or []}
    refs |= {c["reference"] for c in result.comparisons}
    return tuple(sorted(refs))


def _stderr(text: str) -> None:
    import sys

    print(f"gfbopt: {text}", file=sys.stderr, flush=True)


def write_result(result: StudyResult, results_root: Path, *, force: bool = False,
                 notify=None) -> Path:
    """Write every table, figure, ``summary.json`` and ``README.md`` of ``result`` into
    ``results_root/NAME/`` and refresh ``results_root/index.md``; returns the folder.

    Each file is written atomically (:mod:`.output`); a file there that gfbopt did not write
    is kept (a warning through ``notify``, default stderr) unless ``force``.  Call
    :func:`prepare_output` before computing to find an unwritable folder early (this
    function checks again)."""
    notify = notify or _stderr
    study = result.study
    out = prepare_output(Path(results_root), study.name, force=force)
    names = [*result.tables, *result.figures, "summary.json", "README.md"]
    allowed = writable_names(out, names, force, notify)
    files = []
    for name, table in result.tables.items():
        if name in allowed:
            write_atomic(out / name, lambda tmp, t=table: t.to_csv(tmp, index=False,
                                                                  float_format="%.7g"))
            files.append(name)
    from ..plotting import save_figure

    for name, figure in result.figures.items():
        if name in allowed:
            write_atomic(out / name, lambda tmp, f=figure: save_figure(f, tmp))
            files.append(name)
    summary = {
        "name": study.name, "kind": study.kind, "title": study.spec["title"],
        "source": study.spec["source"], "problem_file": study.file, **result.answer,
        "consistency_checks_hold": result.checks_hold, "checks": result.checks,
        "agrees_with_reference": result.agreement,
        "largest_deviation": largest_deviation(result), "comparisons": result.comparisons,
        "files": files, "wall_time_s": result.wall_time_s, "notes": result.notes,
        "provenance": provenance(**result.options)}
    if "summary.json" in allowed:
        write_text_atomic(out / "summary.json", json.dumps(_jsonable(summary), indent=2,
                                                           ensure_ascii=False) + "\n")
    if "README.md" in allowed:
        write_text_atomic(out / "README.md", readme(result, summary))
    write_index(Path(results_root), notify=notify, force=force)
    return out


def _cell(text) -> str:
    """Text for a Markdown table cell (a '|' would end the cell)."""
    return str(text).replace("|", "\\|")


def _fmt(value: float) -> str:
    return "not found" if not math.isfinite(value) else f"{value:.4g}"


def readme(result: StudyResult, summary: dict) -> str:
    """A generated page per study: what, source, physics options, checks, comparisons,
    files and the meaning and unit of every column."""
    study = result.study
    prov = summary["provenance"]
    commit = (prov["source_commit"] or "not a git checkout")[:12]
    dirty = " (with uncommitted changes)" if prov["source_dirty"] else ""
    lines = [result.verdict, ""] if result.verdict else []      # the answer first
    lines += [f"# {study.spec['title']}", "",
             f"*Generated by `{study.command}`; do not edit.*", "",
             f"**Source:** {study.spec['source']}", "",
             f"gfbopt {prov['gfbopt_version']}, commit {commit}{dirty}, {prov['date']}; "
             f"{result.wall_time_s:.1f} s.", "", "## Notes", ""]
    lines += [f"- {n}" for n in [*study.spec["notes"], *result.notes]] or ["- none"]
    lines += ["", "## Model", "", "Physics options of each variant (also in summary.json):", ""]
    for label, options in result.options.get("variants", {}).items():
        for o in options if isinstance(options, list) else [options]:
            text = ", ".join(f"{k} = {v}" for k, v in o.items())
            lines.append(f"- **{label}**: {text}")
    extra = {k: v for k, v in result.options.items() if k != "variants"}
    if extra:
        lines.append("- " + ", ".join(f"{k} = {v}" for k, v in extra.items()))
    lines += ["", "## Checks (internal consistency)", ""]
    if result.checks:
        lines += ["| check | value | limit | holds |", "|---|---|---|---|"]
        lines += [f"| {_cell(c['what'])} | {_fmt(c['value'])} | {c['limit']:.4g} | "
                  f"{'yes' if c['passed'] else '**NO**'} |" for c in result.checks]
    else:
        lines.append("none")
    lines += ["", "## Agreement with the published reference", ""]
    if result.comparisons:
        lines += ["| comparison | reference | deviation | tolerance | agrees |",
                  "|---|---|---|---|---|"]
        lines += [f"| {_cell(c['what'])} | {c['reference']} | {_fmt(c['value'])} | "
                  f"{c['limit']:.4g} | {'yes' if c['agrees'] else '**no**'} |"
                  for c in result.comparisons]
    else:
        lines.append("Not compared: the source publishes no values for these results.")
    lines += ["", "## Files and columns", ""]
    refs = _references(result)
    for name in summary["files"]:
        lines.append(f"- [{name}]({name})")
    described = set()
    for name, table in result.tables.items():
        columns = [c for c in table.columns if c not in described]
        if not columns:
            continue
        described |= set(columns)
        lines += ["", f"Columns of {name}:", "", "| column | unit | meaning |", "|---|---|---|"]
        for c in columns:
            try:
                unit, meaning = describe(c, refs)
            except KeyError:         # never lose a computed study over a missing description
                unit, meaning = "?", "not yet described in gfbopt/glossary.py"
            lines.append(f"| `{c}` | {unit} | {_cell(meaning)} |")
    lines += ["", "## Study file keys", "", "| key | | meaning |", "|---|---|---|"]
    lines += [f"| `{k}` | {state} | {_cell(doc)} |"
              for k, state, doc in describe_schema(study.kind)]
    return "\n".join(lines) + "\n"


def write_index(results_root: Path, notify=None, force: bool = False) -> list:
    """Regenerate ``results_root/index.md`` from the studies' ``summary.json`` files; a
    summary that is not gfbopt's (not JSON, no provenance: another tool's) is skipped with
    a warning through ``notify`` (default stderr).  Returns the skipped paths."""
    from .output import marked

    notify = notify or _stderr
    lines = ["# Results", "", "*Generated by `gfbopt run`; do not edit.* "
             f"\"{CHECKS.capitalize()}\" counts the internal checks of a study's "
             "computation (not a verdict on what it studies: a design study's answer is the "
             "first line of its README); \"agrees with the published reference\" says "
             "whether our values reproduce the published ones within the tolerance the "
             "source supports, with the largest deviation.", "",
             f"| study | title | source | {CHECKS} | agrees with the published reference "
             "| date | commit |", "|---|---|---|---|---|---|---|"]
    skipped = []
    for f in sorted(Path(results_root).glob("*/summary.json")):
        s = summary_of(f.parent)
        try:
            n = len(s["checks"])
            ok = sum(c["passed"] for c in s["checks"])
            agree = s["agrees_with_reference"]
            prov = s["provenance"]
            if s.get("largest_deviation"):
                agree += f"; largest deviation: {s['largest_deviation']}"
            commit = (prov.get("source_commit") or "")[:8] + ("+" if prov.get("source_dirty")
                                                               else "")
            row = (f"| [{s['name']}]({f.parent.name}/README.md) | {_cell(s['title'])} | "
                   f"{_cell(s['source'])} | {ok}/{n} | {_cell(agree)} | {prov['date'][:10]} "
                   f"| {commit} |")
        except (TypeError, KeyError, AttributeError):
            if s is None and _is_json(f):        # another writer's JSON (e.g. benchmarks)
                continue
            skipped.append(f)
            notify(f"warning: {f} is not a gfbopt study summary: left out of the index")
            continue
        lines.append(row)
    lines += ["", "`+` after a commit: generated from a checkout with uncommitted changes."]
    index = Path(results_root) / "index.md"
    if index.exists() and not marked(index) and not force:
        notify(f"warning: {index} was not written by gfbopt: not overwritten")
        return skipped
    write_text_atomic(index, "\n".join(lines) + "\n")
    return skipped


def _is_json(path: Path) -> bool:
    try:
        json.loads(path.read_text())
        return True
    except (OSError, ValueError, UnicodeDecodeError):
        return False
