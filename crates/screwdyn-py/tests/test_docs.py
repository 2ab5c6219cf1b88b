"""The screwdyn snippets of the pages for Pinocchio and Robotics Toolbox users run: every
```python block of each page, in order, in one namespace, from the repository root (the other
libraries' calls are in tables and are not run)."""

import os
import re

import pytest

from conftest import ROOT

PAGES = ["docs/from-pinocchio.md", "docs/from-robotics-toolbox.md"]


def python_blocks(text):
    return re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)


@pytest.mark.parametrize("page", PAGES)
def test_page_snippets_run(page, monkeypatch):
    blocks = python_blocks((ROOT / page).read_text(encoding="utf-8"))
    assert len(blocks) >= 3, f"{page} has {len(blocks)} python blocks"
    monkeypatch.chdir(ROOT)
    namespace = {"__name__": "__docs__"}
    for k, block in enumerate(blocks):
        code = compile(block, f"{page} (python block {k + 1})", "exec")
        exec(code, namespace)  # noqa: S102 — the documentation's own examples


def test_readme_links_both_pages():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    for page in PAGES:
        assert f"({page})" in readme, page
    assert os.path.exists(ROOT / "docs" / "from-pinocchio.md")
