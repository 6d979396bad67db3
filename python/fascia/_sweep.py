"""Parameter studies on Dask distributed (Debian's python3-distributed): one simulation per
parameter set, each loaded and run in a worker, the outputs gathered into a pandas DataFrame."""
import itertools
import os
import tempfile
import time as _time
import traceback

import numpy as np

from ._errors import ParameterError

_PACKAGE_PARENT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _parameter_sets(parameters):
    """A list of {path.param: value}: given so, or the product of a {path.param: [values]} grid."""
    if isinstance(parameters, dict):
        keys = list(parameters)
        return [dict(zip(keys, values)) for values in itertools.product(*(parameters[k] for k in keys))]
    sets = list(parameters)
    if not all(isinstance(p, dict) for p in sets):
        raise ParameterError("sweep(): parameters is a list of {'path.param': value} or a dict of value lists")
    return sets


def _outputs_of(sim, outputs):
    """{column: value} for the requested outputs of a finished simulation."""
    row = {}
    for out in outputs:
        if callable(out):
            row[getattr(out, "__name__", "reduction")] = out(sim)
        elif isinstance(out, tuple) and len(out) == 2 and callable(out[1]):
            row[out[0]] = out[1](sim)
        elif out.startswith("monitor:"):
            frame = sim.monitor(out[len("monitor:"):])
            name = out[len("monitor:"):]
            for col in frame.columns:
                row[f"{name}.{col}"] = frame[col].to_numpy()
        elif out.startswith("state:"):
            state, _, array = out[len("state:"):].rpartition(".")
            row[out[len("state:"):]] = np.array(getattr(sim.state(state), array))
        elif out in ("time", "step_count"):
            row[out] = getattr(sim, out)
        else:
            raise ParameterError(f"sweep(): unknown output '{out}' (monitor:NAME, state:NAME.x, time, "
                                 "step_count, or a function of the simulation)")
    return row


def run_one(scene, params, outputs, steps, until, threads, output_dir):
    """One run of a sweep (in a worker): a row of outputs, or the error that stopped it."""
    import fascia
    start = _time.perf_counter()
    row = {"error": None}
    try:
        os.makedirs(output_dir, exist_ok=True)
        fascia.set_threads(threads)
        built = scene() if callable(scene) else scene
        sim = fascia.Simulation(built, output_dir=output_dir, overrides=params)
        try:
            if steps is not None:
                sim.run(steps=steps)
            elif until is not None:
                sim.run(time=until)
            else:
                sim.run(steps=100)
            row.update(_outputs_of(sim, outputs))
        finally:
            sim.close()
    except Exception as e:  # noqa: BLE001 (a failing set is a row with its error, never a lost sweep)
        row["error"] = f"{type(e).__name__}: {e}"
        row["traceback"] = traceback.format_exc()
    row["wall_s"] = _time.perf_counter() - start
    return row


def sweep(scene, parameters, outputs=(), client=None, steps=None, time=None, threads=1, n_workers=2,
          output_dir=None):
    """Runs one simulation per parameter set on Dask and returns a pandas DataFrame, one row each.

    scene: an XML file's path, a fascia.Node, or a function returning one (importable by the
    workers). parameters: a list of {"path/to/component.parameter": value} (or a dict of value
    lists: their product). outputs: "monitor:NAME" (each column of the Monitor's CSV, as an
    array), "state:NAME.x" (a final node array), "time", "step_count", or functions of the
    simulation (a reduction; the column is the function's name; or (column, function) pairs).
    client: None starts a LocalCluster of n_workers processes on this machine (one thread each)
    and closes it after; a scheduler address ("tcp://host:8786") or a distributed.Client runs on
    that cluster. steps or time: how far each run goes (default 100 steps). threads: OpenMP
    threads per run. output_dir: the runs write into output_dir/run_0000 ... (default a temporary
    folder). A set that fails is a row whose "error" says why; the others go on."""
    import pandas
    from distributed import Client, LocalCluster, as_completed

    sets = _parameter_sets(parameters)
    if isinstance(scene, (str, os.PathLike)):
        scene = os.path.abspath(os.fspath(scene))
    base = output_dir or tempfile.mkdtemp(prefix="fascia-sweep-")
    own = None
    if client is None or isinstance(client, str):
        if client is None:
            # the workers are new processes: they find fascia where this process does
            os.environ["PYTHONPATH"] = os.pathsep.join(p for p in [_PACKAGE_PARENT, os.environ.get("PYTHONPATH")] if p)
            own = LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True, dashboard_address=None)
            client = Client(own)
        else:
            client = Client(client)
        close_client = True
    else:
        close_client = False
    try:
        futures = [client.submit(run_one, scene, p, list(outputs), steps, time, threads,
                                 os.path.join(base, f"run_{i:04d}"), pure=False) for i, p in enumerate(sets)]
        index = {f.key: i for i, f in enumerate(futures)}
        rows = [None] * len(sets)
        for f in as_completed(futures):
            try:
                rows[index[f.key]] = f.result()
            except Exception as e:  # noqa: BLE001 (a lost worker: that row's error)
                rows[index[f.key]] = {"error": f"{type(e).__name__}: {e}"}
    finally:
        if close_client:
            client.close()
        if own is not None:
            own.close()
    table = pandas.DataFrame([{**p, **r, "output_dir": os.path.join(base, f"run_{i:04d}")}
                              for i, (p, r) in enumerate(zip(sets, rows))])
    return table
