"""Sweeps: many scenario points on a Dask cluster (a LocalCluster by default), one results table.

``spec`` (the sweep file), ``points`` (expansion, validation, stable ids), ``inputs`` (the files a
point reads), ``task`` (what a worker runs), ``cluster`` (Dask), ``store`` (the output folder,
resuming), ``table`` (Parquet and CSV), ``html`` (sweep.html), ``run`` (all of it).
"""
