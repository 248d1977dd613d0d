"""Tiles built on Dask distributed (docs/world_from_scan.md#how, step 3): a local cluster by default, any running
scheduler with `--scheduler` (as unexmin.batch). A tile that raises is retried, then reported with its
bounds; the others still build."""

import logging
import os
import time
import traceback

from unexmin.worlds.from_scan.tile import build_tile
from unexmin.worlds.from_scan.tiles import describe

CLOSE_TIMEOUT = 60  # [s] for the client and the local cluster to close


def local_cluster(workers, memory_limit):
    """unexmin.batch's LocalCluster (single-threaded processes on the loopback, one task per free worker),
    each worker held to `memory_limit` bytes by its nanny: a tile past it is killed, retried, reported."""
    from unexmin.batch.run import local_cluster as batch_cluster

    no_spill = {  # tiles hold arrays, not Dask data: nothing to spill
        "distributed.worker.memory.target": False,
        "distributed.worker.memory.spill": False,
        "distributed.worker.memory.pause": False,
        "distributed.worker.memory.terminate": 0.98,
    }
    # a tile's failure is reported by run_tiles, once, with its bounds: Dask's own log lines silenced
    return batch_cluster(workers, no_spill, memory_limit=int(memory_limit), silence_logs=logging.CRITICAL)


def open_client(workers, memory_limit, scheduler=None):
    """(client, cluster): a client of the scheduler at `scheduler`, cluster None; or of a new local cluster
    (local_cluster) whose workers are each bound to cores of their own (cores.BindToCores)."""
    from dask.distributed import Client

    if scheduler:
        return Client(scheduler, timeout=30), None
    from unexmin.worlds.from_scan.cores import BindToCores, cores_for

    cluster = local_cluster(workers, memory_limit)
    client = Client(cluster)
    try:
        client.register_plugin(BindToCores(cores_for(workers)))
    except BaseException:
        _close(client, cluster)
        raise
    return client, cluster


def _failure(tile, layout, error):
    return {"index": tile["index"], "tile": describe(tile, layout["axis"]), "error": error}


def run_tiles(layout, options, workers, memory_limit, scheduler=None, retries=1, bar=None, log=None):
    """Build every tile of `layout` (build_tile with `options`). Returns (results by tile index, failures:
    dicts of index, tile (its bounds in words) and error). workers = 0: one after the other in this
    process, without Dask. `bar`: a tqdm bar advanced per tile."""
    results, failures = {}, []
    tiles = layout["tiles"]
    if workers == 0 and not scheduler:
        for tile in tiles:
            for attempt in range(retries + 1):
                try:
                    results[tile["index"]] = build_tile(tile, layout, **options)
                    break
                except Exception as e:  # reported with the tile's bounds below, never dropped
                    if attempt == retries:
                        failures.append(_failure(tile, layout, f"{type(e).__name__}: {e}"))
            if bar is not None:
                bar.update(1)
        return results, failures
    from dask.distributed import as_completed

    client, cluster = open_client(workers, memory_limit, scheduler)
    try:
        if log is not None:
            where = scheduler or f"a local cluster of {workers} workers of {memory_limit / 1e9:.2f} GB"
            log(f"{len(tiles)} tiles on {where}; Dask dashboard: {client.dashboard_link}")
        stamp = f"{os.getpid()}-{time.monotonic_ns()}"
        futures = {
            client.submit(
                build_tile,
                tile,
                layout,
                **options,
                key=f"unexmin-tile-{tile['index']:04d}-{stamp}",
                retries=retries,
                pure=False,
                priority=int(tile.get("estimate", 0)),  # the largest tiles first: no long one left for the end
            ): tile
            for tile in tiles
        }
        for future in as_completed(futures):
            tile = futures[future]
            try:
                results[tile["index"]] = future.result()
            except Exception as e:  # the tile's own error after its retries, or its worker lost each time
                failures.append(_failure(tile, layout, f"{type(e).__name__}: {e}".strip()))
                if log is not None and not isinstance(e, ValueError):
                    log("".join(traceback.format_exception_only(type(e), e)).strip())
            if bar is not None:
                bar.update(1)
                bar.set_postfix(failed=len(failures))
            future.release()
    finally:
        _close(client, cluster)
    return results, failures


def _close(client, cluster):
    """Close the client and the local cluster; on a loaded machine a worker may take longer to stop than
    Dask waits (a TimeoutError after every tile was built): the nanny has been told to kill it by then."""
    for thing in (client, cluster):
        if thing is None:
            continue
        try:
            thing.close(timeout=CLOSE_TIMEOUT)
        except (TimeoutError, OSError) as e:  # the results are in; the worker is being killed
            logging.getLogger(__name__).debug("closing %s: %s", type(thing).__name__, e)
