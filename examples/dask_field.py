"""Broccoli field maps of many sequences with dask.distributed: one task per sequence, the results
gathered into one table (a list of rows, one per mapped head).

    PYTHONPATH=build/python /usr/bin/python3 examples/dask_field.py SEQ [SEQ...]

Each task builds its own pipeline (a Pipeline is not thread-safe; one per task) and releases the
GIL while it runs, so a worker's threads run in parallel too. run_plain() is the same work in a
plain loop, for comparison (tests/python/test_dask_field.py checks that both give the same table).
"""
import sys

import cropsight as cs

MODEL = "broccoli-oes-uk"


def field_map_rows(sequence, model=MODEL):
    """The field map of one sequence as rows (dicts): the sequence, the head id, its position in
    the field frame (m), its diameter (mm), whether it is harvestable and how often it was seen."""
    pipe = cs.broccoli.Pipeline(model=model, sets={"track": True})
    for frame in cs.read_sequence(sequence):
        pipe.process(frame)
    return [{"sequence": sequence, "head": h.id, "x": float(h.position[0]), "y": float(h.position[1]),
             "z": float(h.position[2]), "diameter_mm": h.diameter_mm, "harvestable": h.harvestable,
             "frames_seen": h.frames_seen} for h in pipe.field_map()]


def run_plain(sequences, model=MODEL):
    return [row for s in sequences for row in field_map_rows(s, model)]


def run_dask(sequences, client, model=MODEL):
    futures = client.map(field_map_rows, sequences, model=model, pure=False)
    return [row for rows in client.gather(futures) for row in rows]


def main(sequences):
    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        table = run_dask(sequences, client)
    print(f"{len(table)} heads in {len(sequences)} sequences")
    for row in table:
        print(row)


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: dask_field.py SEQ [SEQ...]")
    main(sys.argv[1:])
