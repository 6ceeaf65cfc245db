"""Example 8.3 swept over the incline angle: the friction rolling needs, tan(theta)/3, against
mu_s = 0.25 (docs/python.md). Writes docs/images/sweep-example-8.3.png.

Run from the checkout with the module on the path, e.g.
    PYTHONPATH=build/python python3 docs/python/sweep_plot.py
"""

import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import chasles  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def main():
    scene = chasles.load_scene(os.path.join(ROOT, "examples", "example-8.3-cylinder-incline.yaml"))
    table = chasles.sweep(scene, "theta", "0 deg", "60 deg", 61)
    theta = np.degrees(table["theta"])
    mu_s = 0.25
    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=100)
    ax.plot(theta, table["contact_f_over_N"], label="f/N that rolling needs (chasles)")
    ax.plot(theta[::6], np.tan(np.radians(theta[::6])) / 3, "o", fillstyle="none",
            label="tan(theta)/3 (Example 8.3)")
    ax.axhline(mu_s, color="gray", linestyle="--", label="mu_s = 0.25")
    limit = math.degrees(math.atan(3 * mu_s))
    ax.axvline(limit, color="gray", linestyle=":")
    ax.annotate(f"slips above {limit:.2f} deg", (limit, 0.05), xytext=(4, 0),
                textcoords="offset points")
    ax.set_xlabel("incline angle theta [deg]")
    ax.set_ylabel("friction ratio f/N")
    ax.set_title("Example 8.3: cylinder rolling down an incline")
    ax.legend(loc="upper left")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    out = os.path.join(ROOT, "docs", "images", "sweep-example-8.3.png")
    fig.savefig(out, metadata={"Software": None})
    print(out)


if __name__ == "__main__":
    main()
