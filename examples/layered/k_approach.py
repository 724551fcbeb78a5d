"""K_I at the tip of a pressurized crack as it approaches the interface of two bonded
half-planes (docs/layered-rock.md#what-to-expect): a crack in a stiff bed below a soft
one, and in a soft bed below a stiff one, against the homogeneous value p sqrt(pi a).

    python examples/layered/k_approach.py [--output FIGURE] [--gaps G ...]

runs one ddc2d model per gap (the distance from the upper tip to the interface, in
half-lengths of the crack) and material order, prints the table of K_I / (p sqrt(pi a)) at
the upper and the lower tip, and draws the upper tip's curves (default output
layered_k_approach.png). ddc2d is found as ddc2d.run finds it (DDC2D_EXE, build/, PATH).
"""

import argparse
import math
import tempfile
from pathlib import Path

import ddc2d

#: Young's modulus [MPa] and Poisson's ratio of the stiff and the soft bed
STIFF, SOFT = (40000.0, 0.2), (5000.0, 0.3)
#: Half-length [m], pressure [MPa] and elements of the crack
HALF_LENGTH, PRESSURE, ELEMENTS = 1.0, 10.0, 200
GAPS = (2.0, 1.0, 0.5, 0.25, 0.12, 0.06)


def tip_ks(lower, upper, gap, folder):
    """K_I at the upper and the lower tip of the vertical crack whose upper tip lies `gap`
    half-lengths below the interface y = 0, over p sqrt(pi a)."""
    top = -gap * HALF_LENGTH
    model = ddc2d.Model(None, None, domain="bimaterial", interface_y=0.0,
                        title=f"crack {gap} a below the interface")
    model.material("lower", *lower)
    model.material("upper", *upper)
    model.fracture([0.0, 0.0], [top - 2 * HALF_LENGTH, top], elements=ELEMENTS,
                   condition="traction", bc_s=0.0, bc_n=-PRESSURE, name="crack")
    result = ddc2d.run(model, output=Path(folder) / f"gap_{gap}_{lower[0]:g}.h5")
    griffith = PRESSURE * math.sqrt(math.pi * HALF_LENGTH)
    by_height = sorted(zip(result.tips["y"], result.tips["k1"]))
    return by_height[1][1] / griffith, by_height[0][1] / griffith


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--output", default="layered_k_approach.png", help="the figure")
    parser.add_argument("--gaps", type=float, nargs="+", default=GAPS,
                        help="gaps from the upper tip to the interface [half-lengths]")
    args = parser.parse_args(argv)
    curves = {}
    with tempfile.TemporaryDirectory() as folder:
        for name, lower, upper in (("stiff bed below a soft one", STIFF, SOFT),
                                   ("soft bed below a stiff one", SOFT, STIFF)):
            curves[name] = [tip_ks(lower, upper, gap, folder) for gap in args.gaps]
    print("K_I / (p sqrt(pi a)) at the upper (lower) tip")
    print(f"{'gap / a':>8}  " + "  ".join(f"{name:>28}" for name in curves))
    for k, gap in enumerate(args.gaps):
        cells = [f"{ks[k][0]:.4f} ({ks[k][1]:.4f})" for ks in curves.values()]
        print(f"{gap:8.3g}  " + "  ".join(f"{cell:>28}" for cell in cells))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    for (name, ks), marker in zip(curves.items(), ("o", "s")):
        ax.semilogx(args.gaps, [k[0] for k in ks], marker=marker, label=name)
    ax.axhline(1.0, color="0.5", linestyle="--", label="one material (Griffith)")
    ax.set_xlabel("gap from the upper tip to the interface / half-length a")
    ax.set_ylabel("K_I at the upper tip / (p sqrt(pi a))")
    ax.set_title("A pressurized crack approaching a bed of another stiffness "
                 "(E 40 and 5 GPa)", fontsize="medium")
    ax.legend(fontsize="small")
    ax.grid(True, which="both", linewidth=0.3)
    fig.savefig(args.output, dpi=80)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
