#!/usr/bin/env python3
"""Writes a scene of N balls on a cloth for measuring contact sets (docs/scene-format.md, "Sets
of bodies"): the balls in a square grid 7 cm apart, ball1 rolling at 2 m/s into the others.

  scripts/ball_grid_scene.py N CONTACTS [INTEGRATOR] > scene.yaml
  /usr/bin/time -f '%U + %S s, %M KB' build/bin/chasles check scene.yaml

CONTACTS is one of
  none          no contacts (the cost of reading the bodies alone)
  cloth         one entry `body: all` on the cloth
  cloth-listed  the same contacts written one by one (cloth_ball1, ...)
  pairs         `body: all` on the cloth and `between: all` (every pair of balls)
  pairs-listed  the same contacts written one by one (knock_ball1_ball2, ...)
  collisions    `body: all` on the cloth and `ball_collisions` (events or stepping)
INTEGRATOR is events (default), adaptive or stepping (with a step of 1 ms)."""

import math
import sys

CLOTH = "shape: sphere, radius: R, mu_s: 0.25, mu_k: 0.2, plane: {normal: [0, 0, 1]}"
KNOCK = "shape: sphere, radius: R, restitution: 0.9"


def scene(n, contacts, integrator):
    side = math.ceil(math.sqrt(n))
    lines = ["chasles: 3", "parameters: {R: 28.575 mm, m: 0.17 kg}", "bodies:"]
    for i in range(n):
        moving = ", velocity: [2 m/s, 0.3 m/s, 0]" if i == 0 else ""
        lines.append(f"  - {{name: ball{i + 1}, parts: [{{shape: sphere, radius: R, mass: m}}], "
                     f"initial: {{position: [{0.07 * (i % side):.4f}, {0.07 * (i // side):.4f}, "
                     f"R]{moving}}}}}")
    lines.append("gravity: standard")
    if contacts != "none":
        lines.append("contacts:")
    if contacts.endswith("-listed"):
        lines += [f"  - {{name: cloth_ball{i + 1}, body: ball{i + 1}, {CLOTH}}}" for i in range(n)]
    elif contacts != "none":
        lines.append(f"  - {{name: cloth, body: all, {CLOTH}}}")
    if contacts == "pairs":
        lines.append(f"  - {{name: knock, between: all, {KNOCK}}}")
    if contacts == "pairs-listed":
        lines += [f"  - {{name: knock_ball{a + 1}_ball{b + 1}, body: ball{a + 1}, "
                  f"with: ball{b + 1}, other_radius: R, {KNOCK}}}"
                  for a in range(n) for b in range(a + 1, n)]
    lines += ["simulation:", "  until: 1 s", f"  integrator: {integrator}",
              "  output_interval: 0.1 s"]
    if integrator == "stepping":
        lines.append("  step: 1 ms")
    if contacts == "collisions":
        lines.append("  ball_collisions: {restitution: 0.9}")
    return "\n".join(lines) + "\n"


def main():
    kinds = ("none", "cloth", "cloth-listed", "pairs", "pairs-listed", "collisions")
    if len(sys.argv) not in (3, 4) or sys.argv[2] not in kinds or not sys.argv[1].isdigit():
        print(__doc__, file=sys.stderr)
        return 2
    integrator = sys.argv[3] if len(sys.argv) == 4 else "events"
    sys.stdout.write(scene(int(sys.argv[1]), sys.argv[2], integrator))
    return 0


if __name__ == "__main__":
    sys.exit(main())
