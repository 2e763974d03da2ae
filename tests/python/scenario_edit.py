"""Editing a shipped scenario's TOML text into a new mission, as a user would copy and change one."""
from __future__ import annotations

import re


def set_key(text: str, section: str, key: str, value: str) -> str:
    """`key = value` inside [section] of a TOML text (the first such key after the header)."""
    start = text.index(f"[{section}]")
    end = text.find("\n[", start + 1)
    end = len(text) if end < 0 else end
    body, n = re.subn(rf"(?m)^{key} = \S+", f"{key} = {value}", text[start:end], count=1)
    assert n == 1, (section, key)
    return text[:start] + body + text[end:]
