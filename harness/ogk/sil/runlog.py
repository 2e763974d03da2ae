"""Append-only record of the finished runs of a campaign, to keep them through a fault, a Ctrl-C
or a kill, and to resume.

File (`<json>.runs.jsonl` next to a campaign's JSON), one JSON object per line:
  line 1   {"schema": "ogk.runlog/1", "key": {...}}   what the runs depend on (the mission says:
           scenario SHA-256, seed, truth, guidance, dispersions, settings, tables)
  then     one object per finished run, {"run_id": i, ...} (the mission's per-run record), appended
           and flushed as each chunk finishes; NaN written as NaN (Python's json), floats as their
           shortest repr, so a record read back is bit-identical to the one written.
A campaign started without `resume` truncates the file. With `resume` the records of a file whose
key equals the campaign's are kept (a truncated last line, from a kill mid-write, is dropped);
a file with another key is refused (OgkInputError). A run id present twice keeps its last record
(the same numbers: a run depends only on the key and its id).
"""
from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from ogk_bindings.errors import OgkInputError

SCHEMA = "ogk.runlog/1"


def _canonical(value: Any) -> str:
    return json.dumps(value, sort_keys=True)


class RunLog:
    """The run file of one campaign (see module doc)."""

    def __init__(self, path: str | Path, key: dict[str, Any], resume: bool = False) -> None:
        self.path = Path(path)
        self.key = json.loads(_canonical(key))
        self.records: dict[int, dict[str, Any]] = {}
        self.resumed = 0
        if resume and self.path.exists():
            self._read()
            self.resumed = len(self.records)
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with open(self.path, "w", encoding="utf-8") as fh:
                fh.write(json.dumps({"schema": SCHEMA, "key": self.key}, sort_keys=True) + "\n")
                fh.flush()
                os.fsync(fh.fileno())

    def _read(self) -> None:
        raw = self.path.read_bytes()
        complete = raw[:raw.rfind(b"\n") + 1]            # a torn last line is dropped
        lines = complete.decode("utf-8").splitlines()
        try:
            header = json.loads(lines[0]) if lines else None
        except json.JSONDecodeError:
            header = None
        if not isinstance(header, dict) or header.get("schema") != SCHEMA:
            raise OgkInputError(f"not a run file ({SCHEMA})", path=self.path, key="--resume")
        if _canonical(header.get("key")) != _canonical(self.key):
            theirs = header.get("key") or {}
            diff = sorted(k for k in set(theirs) | set(self.key) if theirs.get(k) != self.key.get(k))
            raise OgkInputError(f"belongs to another campaign (differs in {', '.join(diff)}); "
                                "run without --resume to start over", path=self.path,
                                key="--resume")
        for line in lines[1:]:
            rec = json.loads(line)
            self.records[int(rec["run_id"])] = rec
        if len(complete) != len(raw):
            with open(self.path, "r+b") as fh:
                fh.truncate(len(complete))

    def append(self, records: list[dict[str, Any]]) -> None:
        """Appends finished runs (one line each) and flushes them to disk."""
        with open(self.path, "a", encoding="utf-8") as fh:
            fh.write("".join(json.dumps(r) + "\n" for r in records))
            fh.flush()
            os.fsync(fh.fileno())
        for r in records:
            self.records[int(r["run_id"])] = r
