# SPDX-License-Identifier: GPL-3.0-or-later
"""One CSV file, one block of rows per model: the study files (gci.csv, levels.csv,
error_vs_runtime.csv) that several studies of the same case share."""
import csv
import os


def write_model_rows(path, columns, model, rows):
    """Write rows (dicts; column "model" = model) under the header columns to the CSV at path,
    after the rows of other models already there (mapped onto columns: missing ones empty, extra
    ones dropped); this model's earlier rows are replaced. Written to path.tmp and renamed, so
    the file is never half-written."""
    kept = []
    if os.path.isfile(path):
        with open(path, newline="") as f:
            kept = [r for r in csv.DictReader(f) if r.get("model") != model]
    with open(path + ".tmp", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, restval="", extrasaction="ignore",
                           lineterminator="\n")
        w.writeheader()
        w.writerows(kept + rows)
    os.replace(path + ".tmp", path)


def tag_file_rows(src, dst, model):
    """Copy the rows of the single-model CSV src into dst as model's block (a leading "model"
    column; dst's rows of other models kept, model's earlier rows replaced)."""
    with open(src, newline="") as f:
        reader = csv.DictReader(f)
        rows = [dict(r, model=model) for r in reader]
        columns = ["model"] + [c for c in reader.fieldnames if c != "model"]
    write_model_rows(dst, columns, model, rows)


if __name__ == "__main__":
    import sys

    if len(sys.argv) != 5 or sys.argv[1] != "tag":
        sys.exit("usage: model_csv.py tag SRC DST MODEL")
    tag_file_rows(*sys.argv[2:5])
