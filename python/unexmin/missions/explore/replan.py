"""The team's plan at every map read (e: the Explorer): where each robot goes next, a frontier goal or home
(plan.py finds the frontiers, goals and paths on the grid; budget.py says when to turn)."""

import numpy as np

from unexmin.missions.explore.plan import Graph, ball_mask, choose_goals, frontiers, gain_map, path_to, traversable


def replan(e, t):
    """At a map read (sim time `t` [s]): each robot out gets a path on the grid to a frontier goal, or home when its
    budget runs low or no frontier is left within its reach."""
    o, po = e.o, e.po
    spheres = [(a.nav.p, 0.7) for a in e.agents]
    base = traversable(e.grid, po, e.surface_z, spheres)
    front = frontiers(e.grid, e.surface_z, po)
    gain = gain_map(e.grid, po)
    searches, graphs = {}, {}
    for a in e.agents:
        if a.mode == "home":
            continue
        mask = base.copy()
        for b in e.agents:  # the other robots are obstacles
            if b is not a:
                mask &= ~ball_mask(e.grid, b.nav.p, o.robot_clearance)
        g = Graph(e.grid, mask)
        node = g.nearest_node(a.nav.p, 1.0)
        if node < 0:
            e.event(t, a.name, "no_free_cell", f"no traversable cell within 1 m of {a.nav.p.round(2).tolist()}")
            continue
        graphs[a.name] = g
        searches[a.name] = g.distances(node)
    joules_per_m = max([a.energy / a.travelled_est for a in e.agents if a.travelled_est > 5.0] + [20.0])
    for a in e.agents:
        if a.name not in searches:
            continue
        home = path_to(graphs[a.name], searches[a.name], a.home)
        a.home_m = home[1] if home else float(np.linalg.norm(a.nav.p - a.home)) * 1.5
        if a.mode == "explore":
            go, why = e.budget.must_return(t, a.energy, a.home_m, o.speed, joules_per_m)
            if go:
                _go_home(e, a, t, home, "budget " + why)
    exploring = {n: s for n, s in searches.items() if _agent(e, n).mode == "explore"}
    goals = {}
    for name in exploring:
        busy = [b.goal for b in e.agents if b.name != name and b.goal is not None and b.mode == "explore"]
        busy += [goal for goal, _, _ in goals.values()]
        chosen = choose_goals(graphs[name], e.grid, front, gain, {name: exploring[name]}, busy, po, e.avoid)
        goals.update(chosen)
        a = _agent(e, name)
        if name in chosen:
            goal, path, _ = chosen[name]
            a.goal, a.idle = goal, 0
            a.set_path(path, t)
        elif a.idle + 1 < o.idle_replans or _crowded(e, a):
            # turning where it is, its sensors may yet open a way on; a teammate near it may be in its way
            a.idle += 0 if _crowded(e, a) else 1
            a.path, a.goal = None, None
        else:
            home = path_to(graphs[name], searches[name], a.home)
            _go_home(e, a, t, home, "explored: no frontier left within reach")
    for a in e.agents:
        if a.mode == "return" and a.name in searches:
            home = path_to(graphs[a.name], searches[a.name], a.home)
            if home is not None:
                a.set_path(home[0], t)


def _crowded(e, a):
    """True when another robot still out is within 3 m of `a` (it may block a's way, not the frontiers')."""
    return any(b is not a and b.mode != "home" and np.linalg.norm(b.nav.p - a.nav.p) < 3.0 for b in e.agents)


def _go_home(e, a, t, home, why):
    """`a` turns for home (`home`: its path and length on the grid, or None: straight) because of `why`."""
    a.mode, a.why, a.goal = "return", why, None
    if home is not None:
        a.set_path(home[0], t)
    else:
        a.set_path([a.home], t)
        e.event(t, a.name, "no_path_home", "flying straight to the start")
    e.event(t, a.name, "return", why)


def _agent(e, name):
    return next(a for a in e.agents if a.name == name)
