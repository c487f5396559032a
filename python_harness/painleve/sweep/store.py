# SPDX-License-Identifier: BSD-2-Clause
"""Where a sweep's results go, written as batches finish so an interrupted
sweep loses nothing and resumes where it stopped.

- `results.csv`: one file; each batch is appended as whole lines and flushed
  to disk. A line cut by a crash is dropped on resume.
- `results.parquet`: a directory of part files (one per batch, written to a
  temporary name and renamed, so a part is either whole or absent), which
  pandas, pyarrow and dask read as one table.

Beside the results, `<out>.sweep.json` (CSV) or `<out>/_sweep.json` (Parquet;
readers skip names starting with '_') records what the sweep is: a resumed
run must be the same sweep on the same FMU."""
import json
import os
import pathlib

import numpy as np
import pandas as pd

# The columns of every result row, in order, with their types (nullable where a case may not run).
COLUMNS = {
    "id": "int64", "status": "string", "message": "string",
    "theta0": "float64", "phi0": "float64", "delta": "float64", "epsilon": "float64", "v0": "float64",
    "w10": "float64", "alpha": "float64", "mu": "float64",
    "theorem": "Int64", "iwc": "boolean", "w": "float64", "theta": "float64", "phi": "float64", "v": "float64",
    "t_return": "float64", "compression": "float64", "stick": "float64", "lift_off": "float64",
    "flight_back": "float64", "events": "Int64",
    "e": "float64", "predicted_w": "float64", "predicted_phi": "float64", "w1_star": "float64",
    "predicts_iwc": "boolean", "w_error": "float64", "phi_error": "float64", "theta_error": "float64",
    "time_scale": "float64",
}


class StoreError(ValueError):
    """The output cannot hold this sweep; the message says what to change."""


def as_frame(rows):
    """Rows (tuples in COLUMNS' order, or dicts) as a DataFrame with exactly COLUMNS, in order and typed."""
    df = pd.DataFrame(rows, columns=list(COLUMNS))
    return df.astype(COLUMNS)


class ResultStore:
    def __init__(self, path):
        self.path = pathlib.Path(path)
        suffix = self.path.suffix.lower()
        if suffix == ".csv":
            self.kind, self.meta = "csv", self.path.with_name(self.path.name + ".sweep.json")
        elif suffix in (".parquet", ".pq"):
            self.kind, self.meta = "parquet", self.path / "_sweep.json"
        else:
            raise StoreError(f"--out {path}: name the results file with .csv or .parquet")
        self._parts = 0

    def open(self, identity):
        """Prepares the output for the sweep `identity` (a dict); returns the ids already done."""
        if self.meta.exists():
            old = json.loads(self.meta.read_text())
            if old != identity:
                changed = sorted(k for k in set(old) | set(identity) if old.get(k) != identity.get(k))
                raise StoreError(f"{self.path} holds another sweep (its {', '.join(changed)} differ): "
                                 f"run the same command to resume it, or pass a new --out")
        elif self.path.exists() and (self.kind == "csv" or any(self.path.iterdir())):
            raise StoreError(f"{self.path} exists but was not written by `painleve sweep`: pass a new --out")
        if self.kind == "parquet":
            self.path.mkdir(parents=True, exist_ok=True)
        else:
            self.path.parent.mkdir(parents=True, exist_ok=True)
        self.meta.write_text(json.dumps(identity, indent=1))
        return self._done_ids()

    def _done_ids(self):
        if self.kind == "csv":
            if not self.path.exists() or self.path.stat().st_size == 0:
                return np.array([], dtype=np.int64)
            self._drop_cut_line()
            return pd.read_csv(self.path, usecols=["id"])["id"].to_numpy(np.int64)
        import pyarrow.parquet as pq
        parts = sorted(self.path.glob("part-*.parquet"))
        self._parts = len(parts)
        if not parts:
            return np.array([], dtype=np.int64)
        return np.concatenate([pq.read_table(p, columns=["id"])["id"].to_numpy() for p in parts]).astype(np.int64)

    def _drop_cut_line(self):
        """A crash in the middle of a write leaves a last line without its newline: drop it."""
        with open(self.path, "rb+") as f:
            data = f.read()
            if data and not data.endswith(b"\n"):
                f.truncate(data.rfind(b"\n") + 1)

    def append(self, df):
        if df.empty:
            return
        if self.kind == "csv":
            new = not self.path.exists() or self.path.stat().st_size == 0
            text = df.to_csv(index=False, header=new)
            with open(self.path, "a", encoding="utf-8") as f:
                f.write(text)
                f.flush()
                os.fsync(f.fileno())
            return
        name = self.path / f"part-{self._parts:06d}-{int(df['id'].iloc[0]):012d}.parquet"
        self._parts += 1
        tmp = name.with_name("_" + name.name + ".tmp")
        df.to_parquet(tmp, index=False)
        os.replace(tmp, name)

    def read(self, columns=COLUMNS):
        """All rows written so far, sorted by id: `columns` ({name: type}) typed, in that order (the rod's
        sweep's), or every column as written (None: a body's sweep, typed by sweep.body.typed)."""
        if self.kind == "csv":
            df = pd.read_csv(self.path, keep_default_na=False, na_values=[""])
            for name in ("status", "message"):
                df[name] = df[name].fillna("")
        else:
            df = pd.read_parquet(self.path)
        if columns is not None:
            df = df[list(columns)].astype(columns)
        return df.sort_values("id", ignore_index=True)
