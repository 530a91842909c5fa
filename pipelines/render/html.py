"""Self-contained HTML pages: one file that opens anywhere (images embedded as base64 data URIs).

Small builders (no template engine): :func:`page` wraps sections in a document with its own CSS,
:func:`table` renders rows of dicts, :func:`image` embeds a PNG, :func:`grid` places blocks side by
side (one column per design in ``gearfe compare``), :func:`pre` shows a text file (the case).
Every text is HTML-escaped; numbers are formatted with 4 significant digits.
"""

from __future__ import annotations

import base64
import html
from pathlib import Path

__all__ = ["page", "table", "image", "grid", "pre", "section", "fmt", "write_page"]

_CSS = """
body { font-family: -apple-system, 'Segoe UI', Helvetica, Arial, sans-serif; margin: 1.5em 2em; color: #1a1a1a;
       background: #ffffff; max-width: 1800px; }
h1 { font-size: 1.5em; border-bottom: 2px solid #334; padding-bottom: .2em; }
h2 { font-size: 1.2em; margin-top: 1.6em; border-bottom: 1px solid #aab; }
h3 { font-size: 1.0em; margin: 1em 0 .4em; }
table { border-collapse: collapse; margin: .5em 0 1em; font-size: .85em; max-width: 100%; }
th, td { border: 1px solid #bbc; padding: .2em .45em; text-align: right; }
th { background: #e8eaf2; font-weight: 600; text-align: center; overflow-wrap: anywhere; }
td { white-space: nowrap; } td:first-child, th:first-child { text-align: left; }
td.text { text-align: left; max-width: 40em; white-space: normal; }
figure { margin: .6em 0 1.2em; } figure img { max-width: 100%; border: 1px solid #ddd; }
figcaption { font-size: .85em; color: #444; margin-top: .2em; }
.grid { display: grid; gap: 1.5em; } .grid > div { min-width: 0; }
.note { color: #555; font-size: .9em; } details { margin: .4em 0 1em; }
pre { background: #f4f4f7; border: 1px solid #ddd; padding: .8em; font-size: .8em; overflow-x: auto; }
.warn { color: #a40000; }
"""


def fmt(v, nd: int = 4) -> str:
    """A table cell: floats with `nd` significant digits, None as '-', the rest as text (escaped)."""
    if v is None:
        return "-"
    if isinstance(v, bool):
        return str(v)
    if isinstance(v, float):
        return f"{v:.{nd}g}"
    return html.escape(str(v))


def table(rows: list[dict], columns: list[str] | None = None, headers: dict | None = None) -> str:
    """An HTML table of `rows` (dicts); `columns` picks and orders keys, `headers` renames them."""
    if columns is None:
        columns = []
        for r in rows:
            columns += [k for k in r if k not in columns]
    headers = headers or {}
    head = "".join(f"<th>{html.escape(headers.get(c, c))}</th>" for c in columns)
    body = "".join("<tr>" + "".join(_cell(r.get(c)) for c in columns) + "</tr>" for r in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _cell(v) -> str:
    """A cell; long texts (notes) left-aligned and wrapped."""
    text = fmt(v)
    return f'<td class="text">{text}</td>' if isinstance(v, str) and len(v) > 40 else f"<td>{text}</td>"


def image(path: Path, caption: str = "", alt: str = "") -> str:
    """A figure with the PNG at `path` embedded (base64), or a note when the file is missing."""
    path = Path(path)
    if not path.is_file():
        return f'<p class="warn">missing image: {html.escape(path.name)}</p>'
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    cap = f"<figcaption>{html.escape(caption)}</figcaption>" if caption else ""
    return (f'<figure><img alt="{html.escape(alt or path.name)}" src="data:image/png;base64,{data}">'
            f"{cap}</figure>")


def grid(blocks: list[str], columns: int | None = None) -> str:
    """Blocks side by side in `columns` equal columns (default: all in one row)."""
    n = columns or max(1, len(blocks))
    return f'<div class="grid" style="grid-template-columns: repeat({n}, minmax(0, 1fr));">' + "".join(
        f"<div>{b}</div>" for b in blocks) + "</div>"


def pre(text: str) -> str:
    """Preformatted text (e.g. the case file), escaped."""
    return f"<pre>{html.escape(text)}</pre>"


def section(title: str, *blocks: str, level: int = 2) -> str:
    """A heading and its blocks."""
    return f"<h{level}>{html.escape(title)}</h{level}>" + "".join(blocks)


def page(title: str, *blocks: str) -> str:
    """A complete HTML document with its CSS."""
    return (f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
            f"<style>{_CSS}</style></head><body><h1>{html.escape(title)}</h1>" + "".join(blocks) + "</body></html>\n")


def write_page(path: Path, title: str, *blocks: str) -> Path:
    """Write :func:`page` to `path` (UTF-8)."""
    Path(path).write_text(page(title, *blocks), encoding="utf-8")
    return Path(path)
