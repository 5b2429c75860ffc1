"""A study's results table on disk: Parquet part files, a fixed schema, safe to kill.

Layout of a store directory::

    manifest.json          study name, study-file hash, schema, gfbopt provenance
    parts/part-*.parquet   one file per batch of finished points

Each part is written under a temporary name and moved into place with ``os.replace`` (atomic
on POSIX), so a process killed at any moment (``kill -9`` included) leaves only whole parts —
a half-written temporary file is ignored and its points are computed again on resume.  A single
Parquet file appended with row groups is unreadable after such a kill, and a directory of parts
read without a fixed schema silently drops columns that appear later: hence one schema, fixed
when the store is created, applied to every part and to the read.

Every row carries the point key (``point``); :meth:`ResultStore.read` returns each point once
(the last write wins), so a resumed study ends with every point exactly once.
"""
from __future__ import annotations

import json
import os
import uuid
from pathlib import Path
from typing import Iterable, Optional

import pandas as pd

from ..errors import ParameterError

#: Column types a schema may use, and their pyarrow types.
TYPES = ("float64", "int64", "bool", "string")


def _arrow_schema(schema: dict):
    import pyarrow as pa

    kinds = {"float64": pa.float64(), "int64": pa.int64(), "bool": pa.bool_(),
             "string": pa.string()}
    return pa.schema([(name, kinds[kind]) for name, kind in schema.items()])


def _conform(rows: list[dict], schema: dict) -> pd.DataFrame:
    """Rows → a DataFrame with exactly the schema's columns and types (missing → null).

    A column the schema does not know is refused: it would be lost on read.
    """
    extra = sorted({k for r in rows for k in r} - set(schema))
    if extra:
        raise ParameterError("row", extra[0], f"is not a column of this study's table "
                             f"(schema: {', '.join(schema)})")
    frame = pd.DataFrame.from_records(rows, columns=list(schema))
    for name, kind in schema.items():
        col = frame[name]
        if kind == "float64":
            frame[name] = pd.to_numeric(col, errors="coerce").astype("float64")
        elif kind == "int64":
            frame[name] = pd.to_numeric(col, errors="coerce").astype("Int64")
        elif kind == "bool":
            frame[name] = col.astype("boolean")
        else:
            frame[name] = col.astype("string")
    return frame


class ResultStore:
    """One study's table of results on disk (see the module docstring).

    Use :meth:`create` to start (or resume) a store and :meth:`append` to add finished rows;
    :meth:`read` returns the whole table as one DataFrame.
    """

    def __init__(self, directory: Path, manifest: dict):
        self.directory = Path(directory)
        self.manifest = manifest
        self.schema: dict = manifest["schema"]

    # ------------------------------------------------------------------ opening
    @classmethod
    def create(cls, directory, *, study: str, study_hash: str, schema: dict,
               metadata: Optional[dict] = None, resume: bool = False) -> "ResultStore":
        """Open the store in ``directory`` for study ``study`` (file hash ``study_hash``).

        resume=False: an existing store is kept aside (renamed ``<dir>.previous-N``) and a new
        one started — nothing computed is ever deleted.  resume=True: the existing store is
        reused; it must belong to the same study file (same hash), otherwise ParameterError.
        """
        directory = Path(directory)
        for name, kind in schema.items():
            if kind not in TYPES:
                raise ParameterError(f"schema.{name}", kind, f"must be one of {', '.join(TYPES)}")
        if "point" not in schema:
            raise ParameterError("schema", list(schema), "must contain the point key 'point'")
        manifest_path = directory / "manifest.json"
        if manifest_path.is_file():
            old = json.loads(manifest_path.read_text())
            if resume:
                if old.get("study_hash") != study_hash:
                    raise ParameterError(
                        "--resume", str(directory), f"holds results of another study "
                        f"({old.get('study')!r}, file hash {old.get('study_hash', '?')[:12]}) "
                        f"than this one ({study!r}, {study_hash[:12]}); refusing to mix them")
                return cls(directory, old)
            k = 1
            while Path(f"{directory}.previous-{k}").exists():
                k += 1
            os.replace(directory, f"{directory}.previous-{k}")
        elif resume and directory.exists() and any(directory.iterdir()):
            raise ParameterError("--resume", str(directory), "is not a gfbopt results store "
                                 "(no manifest.json); refusing to write into it")
        (directory / "parts").mkdir(parents=True, exist_ok=True)
        manifest = {"study": study, "study_hash": study_hash, "schema": schema,
                    "metadata": metadata or {}}
        tmp = directory / f".manifest.{uuid.uuid4().hex}.tmp"
        tmp.write_text(json.dumps(manifest, indent=2))
        os.replace(tmp, manifest_path)
        return cls(directory, manifest)

    # ------------------------------------------------------------------ writing
    def append(self, rows: Iterable[dict]) -> Optional[Path]:
        """Write ``rows`` as one new part (atomic); returns its path (None if no rows)."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        rows = list(rows)
        if not rows:
            return None
        frame = _conform(rows, self.schema)
        table = pa.Table.from_pandas(frame, schema=_arrow_schema(self.schema),
                                     preserve_index=False)
        table = table.replace_schema_metadata(
            {"gfbopt": json.dumps({"study": self.manifest["study"],
                                   "study_hash": self.manifest["study_hash"],
                                   **self.manifest.get("metadata", {})}, default=str)})
        name = f"part-{uuid.uuid4().hex}.parquet"
        tmp = self.directory / "parts" / f".{name}.tmp"
        pq.write_table(table, tmp)
        final = self.directory / "parts" / name
        os.replace(tmp, final)
        return final

    # ------------------------------------------------------------------ reading
    def parts(self) -> list[Path]:
        """The finished part files (temporary files of an interrupted write excluded)."""
        return sorted((self.directory / "parts").glob("part-*.parquet"),
                      key=lambda p: p.stat().st_mtime_ns)

    def read(self) -> pd.DataFrame:
        """The whole table, one row per point (last write wins), sorted by point."""
        import pyarrow.dataset as ds

        parts = self.parts()
        if not parts:
            return _conform([], self.schema)
        table = ds.dataset([str(p) for p in parts], schema=_arrow_schema(self.schema),
                           format="parquet").to_table()
        frame = table.to_pandas()
        frame = frame.drop_duplicates(subset="point", keep="last")
        return frame.sort_values("point").reset_index(drop=True)

    def done_points(self) -> set:
        """Point keys already stored (skipped on resume)."""
        return set(self.read()["point"].tolist())


def read_results(directory) -> pd.DataFrame:
    """The results table of a study store directory as one pandas DataFrame."""
    directory = Path(directory)
    manifest = directory / "manifest.json"
    if not manifest.is_file():
        raise ParameterError("results", str(directory), "is not a gfbopt results store (no "
                             "manifest.json)")
    return ResultStore(directory, json.loads(manifest.read_text())).read()
