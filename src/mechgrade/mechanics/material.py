"""Material points: a velocity asked of a point that is fixed in no body, while a body's
material point sits there, is probably meant as the body's point (``coincident(P, Body)``).

A point located from a body's origin but not turning with the body (a disk's contact point
``T`` located from the centre by ``-R*N.y``) moves with the centre: ``vel(T, N)`` is the
velocity of that geometric point, not of the disk's material point at ``T``.
"""

from __future__ import annotations

from ..errors import AuthorWarning, Location, SpecError
from ..expressions.syntax import Attr, Call, Name, Node, name_of, to_text, walk
from ..spec.model import Problem
from .build import Model
from .symbols import identically_zero

_POINT_RATES = {"vel", "acc", "speed", "tangent", "acc_t", "acc_n", "rho", "normal"}


def fixed_in(model: Model, point: str, frame: str) -> bool:
    """Whether ``point`` keeps its place in ``frame`` (relative to a point fixed in it)."""
    try:
        origin = model.language.origin(frame)
    except SpecError:  # a frame without an origin: nothing can be said
        return False
    relative = (model.positions[point] - model.positions[origin]).dt(model.frames[frame])
    return all(identically_zero(model.plain(c))
               for c in relative.to_matrix(model.frames[frame]))


def material_warnings(problem: Problem, model: Model) -> tuple[AuthorWarning, ...]:
    """A warning for each given or objective that asks the velocity (or acceleration) of a
    point fixed in no frame while a body's material point coincides with it."""
    bodies: dict[str, set[str]] = {}
    for c in problem.constraints:
        for node in (*walk(c.lhs.node), *walk(c.rhs.node)):
            # coincident's point may itself be a coincident(...) point: its inner call is walked
            if isinstance(node, Call) and node.func == "coincident" \
                    and isinstance(node.args[0], Name):
                bodies.setdefault(node.args[0].id, set()).add(name_of(node.args[1]))
    for f in problem.frames:
        if f.parent is None or f.origin is None:
            continue
        for p in problem.points:
            # located from the body's origin without the body's own axes: it does not turn
            # with the body (a collar located along the rod by R*Rod.x is meant to slide)
            if p.origin == f.origin and p.position is not None and not any(isinstance(n, Attr) and n.base == f.name
                                                for n in walk(p.position.node)):
                bodies.setdefault(p.name, set()).add(f.name)
    uses: list[tuple[str, Node, Location]] = []
    for g in problem.givens:
        uses.append((g.key.text, g.key.node, g.where))
    for o in problem.objectives:
        uses.append((o.find.text, o.find.node, o.find.where))
        uses += [(g.key.text, g.key.node, g.where) for g in o.givens]
    out = []
    loose: dict[str, bool] = {}
    for text, node, where in uses:
        for call in walk(node):
            if not (isinstance(call, Call) and call.func in _POINT_RATES
                    and isinstance(call.args[0], Name)):
                continue
            point = call.args[0].id
            candidates = sorted(bodies.get(point, ()))
            if not candidates:
                continue
            if point not in loose:
                loose[point] = not any(fixed_in(model, point, f.name) for f in problem.frames)
            if not loose[point]:
                continue
            body = candidates[0]
            wanted = to_text(Call(call.func, (Call("coincident", (Name(point), Name(body))),)
                                  + call.args[1:]))
            out.append(AuthorWarning(
                f"'{to_text(call)}' in '{text}' is the motion of the geometric point {point}, "
                f"which is fixed in no body; {body}'s material point coincides with it: if you "
                f"mean that point, write '{wanted}'", where))
    return tuple(out)
