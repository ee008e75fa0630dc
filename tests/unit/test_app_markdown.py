"""The page shows names and messages as written: Streamlit reads its texts as Markdown (with
$…$ as math), so every markup character is escaped (chaindrive.app.views.plain). CommonMark
§2.4: a backslash before an ASCII punctuation character stands for that character."""

from __future__ import annotations

import re

from hypothesis import given, settings
from hypothesis import strategies as st

from chaindrive.app.views import MARKDOWN_SPECIALS, plain


def _commonmark_unescape(md: str) -> str:
    return re.sub(r"\\([!-/:-@\[-`{-~])", r"\1", md)


@settings(max_examples=200, derandomize=True)
@given(st.text(alphabet=st.sampled_from(sorted(MARKDOWN_SPECIALS) + list("aZ0 ·Ωé")),
               max_size=40))
def test_a_text_reads_back_as_written_and_no_markup_is_left(text: str) -> None:
    md = plain(text)
    assert _commonmark_unescape(md) == text
    # every markup character is escaped: none stands unescaped
    i = 0
    while i < len(md):
        if md[i] == "\\":
            assert md[i + 1] in MARKDOWN_SPECIALS
            i += 2
            continue
        assert md[i] not in MARKDOWN_SPECIALS
        i += 1


def test_formula_bold_and_html_of_a_name_are_escaped() -> None:
    assert plain("$x$ **S1** <b>") == "\\$x\\$ \\*\\*S1\\*\\* \\<b\\>"
