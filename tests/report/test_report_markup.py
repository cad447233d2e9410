"""Report markup checked without a browser: Part 25 citations only are linked to the eCFR (a textbook's "§16.3" is
not a CFR section), figures carry an accessible name (WCAG 2.2 SC 1.1.1), and big tables are stored compressed
losslessly and deterministically (zlib, RFC 1950, as the page's DecompressionStream("deflate") reads it)."""

from __future__ import annotations

import base64
import re
import zlib

from certkit.report.html import linkify, pack_tables, titled_svg


def test_textbook_sections_are_not_cfr_links():
    html = str(linkify("Raymer §16.3, Torenbeek §5.3 and §25.335(a), 14 CFR 25.1505", {"25.335(a)"}))
    assert "§16.3" in html and "section-16.3" not in html and "section-5.3" not in html
    assert 'href="#r25-335-a"' in html and "section-25.1505" in html


def test_figures_get_an_accessible_name():
    svg = str(
        titled_svg(
            '<?xml version="1.0"?>\n<svg xmlns="http://www.w3.org/2000/svg" width="4"><g/></svg>', "V–n diagram <clean>"
        )
    )
    assert 'role="img" aria-label="V–n diagram &lt;clean&gt;"><title>V–n diagram &lt;clean&gt;</title><g/>' in svg


def test_big_tables_are_packed_losslessly_and_small_ones_kept():
    rows = "".join(f'<tr><td>condition {i}</td><td class="num">{i}.0 kn</td></tr>' for i in range(400))
    big = (
        '<div class="table-wrap"><table><thead><tr><th>C</th><th>M</th></tr></thead>'
        f"<tbody>{rows}</tbody></table></div>"
    )
    small = '<div class="table-wrap"><table><tr><td>one</td></tr></table></div>'
    packed = pack_tables(f"<p>a</p>{big}<p>b</p>{small}")
    assert small in packed and big not in packed and 'data-rows="400"' in packed
    data = re.search(r'<script type="application/x-certkit-table">([^<]+)</script>', packed)[1]
    assert zlib.decompress(base64.b64decode(data)).decode() == big
    assert pack_tables(f"{big}") == pack_tables(f"{big}")  # deterministic
