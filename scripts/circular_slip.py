#!/usr/bin/python3
"""Circular-slip limit equilibrium of an undrained (phi = 0) clay slope on a clay foundation: the
reference for the factors of safety of cases/slope_griffiths_lane1999_foundation.toml.

For phi = 0 the moment equilibrium of a rigid body sliding on a circle is exact (the "phi = 0 method"):
    F = R sum(c_u ds) / int (x_c - x) (gamma_1 h_1 + gamma_2 h_2) dx,
h_1 and h_2 the heights of the slope's and the foundation's soil above the arc (the foundation of unit
weight gamma_2 = gamma_ratio gamma_1). The script searches circles (centre on a 1 m grid, radius in 0.5 m
steps) that stay inside the domain and above the rigid base, with c_u1 in the slope (above the toe's
level) and c_u2 = lambda c_u1 in the foundation, and prints the smallest F and its circle.

Usage: circular_slip.py [--lambda 2] [--gamma-ratio 1] [--H 10] [--cot 2] [--D 2] [--c1 0.25] [--crest 30]
[--ahead 40] (c1 is c_u1 / (gamma_1 H); crest and ahead are the lengths of ground behind the crest and before the
toe, m; the defaults are the shipped case's geometry.)
"""
import argparse

import numpy as np

from granflow_files import positive


def smallest_factor(lam, H, cot, D, c1, crest, ahead, gamma_ratio=1.0):
    gamma = 1.0  # F is independent of gamma_1 once c_u is given as a fraction of gamma_1 H
    cu1 = c1 * gamma * H
    base = -(D - 1.0) * H                    # the toe at y = 0, the crest at y = H
    toe = crest + cot * H
    right = toe + ahead
    xs = np.linspace(0.0, right, int(right / 0.02) + 1)
    dx = xs[1] - xs[0]
    # the slope's face only where it lies, so that a steep slope (cot near 0) divides nothing outside it
    ground = np.where(xs < crest, H, 0.0)
    face = (xs >= crest) & (xs < toe)
    ground[face] = H - (xs[face] - crest) / cot
    best = (np.inf, None)
    for xc in np.arange(crest - H, right, 1.0):
        for yc in np.arange(H, H + 6.0 * H, 1.0):
            for R in np.arange(1.0, yc - base + 1e-9, 0.5):
                inside = np.abs(xs - xc) < R
                arc = np.full_like(xs, np.inf)
                arc[inside] = yc - np.sqrt(R * R - (xs[inside] - xc) ** 2)
                below = inside & (arc < ground)
                idx = np.nonzero(below)[0]
                # one slipping body, within the domain's sides
                if len(idx) < 3 or idx[0] == 0 or idx[-1] == len(xs) - 1 or idx[-1] - idx[0] + 1 != len(idx):
                    continue
                # the soil above the arc: the slope's above the toe's level (y = 0), the foundation's below
                slope = ground[idx] - np.maximum(arc[idx], 0.0)
                foundation = np.maximum(-arc[idx], 0.0)
                driving = gamma * np.sum((xc - xs[idx]) * (slope + gamma_ratio * foundation)) * dx
                if driving <= 0.0:
                    continue
                t0, t1 = (np.arcsin(np.clip((xs[k] - xc) / R, -1.0, 1.0)) for k in (idx[0], idx[-1]))
                theta = np.linspace(t0, t1, 400)
                cu = np.where(yc - R * np.cos(theta) < 0.0, lam * cu1, cu1)
                resisting = R * np.trapz(cu * R, theta)
                if resisting / driving < best[0]:
                    best = (resisting / driving, (xc, yc - base, R))
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lambda", dest="lam", type=positive, default=2.0, help="c_u2 / c_u1 of the foundation")
    ap.add_argument("--gamma-ratio", type=positive, default=1.0, help="the foundation's unit weight over the slope's")
    ap.add_argument("--H", type=positive, default=10.0)
    ap.add_argument("--cot", type=positive, default=2.0, help="cot(beta) of the slope")
    ap.add_argument("--D", type=positive, default=2.0, help="depth to the rigid base over H, from the crest")
    ap.add_argument("--c1", type=positive, default=0.25, help="c_u1 / (gamma H)")
    ap.add_argument("--crest", type=positive, default=30.0)
    ap.add_argument("--ahead", type=positive, default=40.0)
    a = ap.parse_args()
    f, circle = smallest_factor(a.lam, a.H, a.cot, a.D, a.c1, a.crest, a.ahead, a.gamma_ratio)
    print(f"lambda = {a.lam:g}, gamma_2 / gamma_1 = {a.gamma_ratio:g}: F = {f:.3f} on the circle of centre ({circle[0]:g}, {circle[1]:g}) m above the base's "
          f"left end, radius {circle[2]:g} m")


if __name__ == "__main__":
    main()
