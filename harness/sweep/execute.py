"""Running the cases of a sweep on Dask: one task per case (the FMU instantiated in the worker),
results cached on disk under the case's key, failures reported instead of stopping the sweep.

By default a LocalCluster with one single-threaded worker process per core (the FMU's fixed-step
modes are single-threaded: processes, not threads, share the cores). With a scheduler address the
cases go to that cluster instead (`dask scheduler` on one machine, `dask worker ADDRESS
--nthreads 1` on each machine with this package and ChainDrive.fmu installed); the cache stays on
the machine that runs the command. A worker lost while it runs a case (killed, out of memory) is
replaced by its nanny and the case runs again elsewhere (Dask retries it; RETRIES more times if
it fails again), so no case is lost to it."""
import contextlib
import json
import os
import pathlib

from .cases import case_key, code_version, run_case

RETRIES = 2


@contextlib.contextmanager
def dask_client(workers=None, scheduler=None):
    """A Dask client of the cluster at `scheduler`, or of a LocalCluster of `workers` (default:
    one per core) single-threaded worker processes, closed afterwards."""
    from dask.distributed import Client, LocalCluster
    if scheduler:
        with Client(scheduler) as client:
            yield client
        return
    n = workers or os.cpu_count() or 1
    with LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        yield client


def _cached(cache, key):
    p = pathlib.Path(cache) / f"{key}.json"
    return json.loads(p.read_text()) if p.exists() else None


def _store(cache, key, result):
    p = pathlib.Path(cache)
    p.mkdir(parents=True, exist_ok=True)
    tmp = p / f"{key}.json.tmp"
    tmp.write_text(json.dumps(result))
    tmp.replace(p / f"{key}.json")  # whole files only: a sweep stopped while writing leaves no half result


def run_cases(cases, cache, client=None, workers=None, scheduler=None, progress=True):
    """Results of the cases (run_case's dicts, in the order of cases) and the number computed now
    (the others came from the cache). Successful results are cached; a failed one is not (it runs
    again next time) and carries its error."""
    version = code_version()
    keys = [case_key(c, version) for c in cases]
    results = {k: _cached(cache, k) for k in keys}
    todo = [(c, k) for c, k in zip(cases, keys) if results[k] is None]
    if todo:
        with contextlib.ExitStack() as stack:
            if client is None:
                client = stack.enter_context(dask_client(workers, scheduler))
            results.update(_compute(client, todo, cache, progress))
    return [results[k] for k in keys], len(todo)


def _compute(client, todo, cache, progress):
    from dask.distributed import as_completed
    from tqdm import tqdm
    futures = {client.submit(run_case, c, key=f"case-{k}", pure=False, retries=RETRIES): (c, k) for c, k in todo}
    out = {}
    with tqdm(total=len(futures), desc="cases", unit="case", disable=not progress) as bar:
        for future in as_completed(futures):
            case, key = futures[future]
            try:
                result = future.result()
            except Exception as e:  # lost on every try (KilledWorker) or not run at all
                result = {"status": "failed", "error": f"{type(e).__name__}: {e}"}
            if result["status"] == "ok":
                _store(cache, key, result)
            out[key] = result
            bar.set_postfix_str(case.label(), refresh=False)
            bar.update()
    return out
