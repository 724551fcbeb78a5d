"""Frictional contact against closed forms and the paper's own results (docs/verification.md;
docs/theory/contact.md#checks-against-closed-forms): the paper's fault that slips and the
one that sticks (input/paper_fault_slip.nml, input/paper_fault_stick.nml), the paper's
Matlab results for 100 elements (tests/reference/ritz2012/), and a weak patch in a strong
fault, which partly sticks."""

import math

import numpy as np

import ddc2d
from conftest import REPO_ROOT
from ddc2d.richardson import extrapolate

E, NU = 50000.0, 0.25
G = E / (2 * (1 + NU))
PAPER = "Ritz, Mutlu & Pollard (2012)"
PAPER_LEVELS = (125, 250, 500)
RITZ = REPO_ROOT / "tests" / "reference" / "ritz2012" / "R2_straight_n100_mu0.6_sf0"


def paper_fault(tmp_path, name, elements):
    """The input file `name` with `elements` elements and no grid (the rows need no field)."""
    text = (REPO_ROOT / "input" / f"{name}.nml").read_text()
    assert "elements = 500" in text
    lines = [line for line in text.replace("elements = 500", f"elements = {elements}")
             .splitlines() if not line.startswith("&grid")]
    path = tmp_path / f"{name}_{elements}.nml"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_paper_fault_slips(solve, record, tmp_path):
    """mu = 0.6, Sf = 1: the stress drop 4.38 MPa; every element slips,
    K_II = 4.38 sqrt(pi) and the peak slip 2 (1 - nu) 4.38 / G at the centre."""
    results = [solve(paper_fault(tmp_path, "paper_fault_slip", n), f"slip{n}")
               for n in PAPER_LEVELS]
    assert all(np.all(r.elements["state"] == 2) for r in results), "every element slips"
    ks = [float(np.mean(np.abs(r.tips["k2"]))) for r in results]
    mesh = f"500 elements (levels {', '.join(map(str, PAPER_LEVELS))})"
    row = record(id="paper-fault-slip-k2", benchmark=f"The paper's fault, mu = 0.6: slips "
                 f"({PAPER})", reference="K_II = dtau sqrt(pi a), dtau = 4.38 MPa (Griffith "
                 "crack under the stress drop)", quantity="K_II at the tips [MPa m^1/2]",
                 value=ks[-1], reference_value=4.38 * math.sqrt(math.pi), tolerance=1e-4,
                 mesh=mesh, order=extrapolate(ks).order)
    assert row["passed"], row
    peaks = [float(np.max(np.abs(r.elements["ds"]))) for r in results]
    row = record(id="paper-fault-slip-peak", benchmark=f"The paper's fault, mu = 0.6: slips "
                 f"({PAPER})", reference="D(0) = 2 (1 - nu) dtau a / G", quantity="peak "
                 "slip [m]", value=peaks[-1], reference_value=2 * (1 - NU) * 4.38 / G,
                 tolerance=2e-3, mesh=mesh, order=extrapolate(peaks).order)
    assert row["passed"], row


def test_paper_fault_sticks(solve, record):
    """mu = 0.7: the strength 1 + 0.7 * 81.25 = 57.9 MPa exceeds the shear 54.13 MPa: every
    element sticks and the DDs are zero."""
    result = solve(REPO_ROOT / "input" / "paper_fault_stick.nml", "stick")
    assert np.all(result.elements["state"] == 1), "every element sticks"
    row = record(id="paper-fault-stick", benchmark=f"The paper's fault, mu = 0.7: sticks "
                 f"({PAPER})", reference="Coulomb: 54.13 < 1 + 0.7 * 81.25 MPa, no slip",
                 quantity="largest |Ds|, |Dn| [m]",
                 value=float(np.max(np.abs([result.elements["ds"], result.elements["dn"]]))),
                 reference_value=0.0, tolerance=1e-15, tolerance_kind="absolute",
                 mesh="500 elements (input/paper_fault_stick.nml)")
    assert row["passed"], row


def test_paper_code_results(solve, record):
    """The paper's Matlab code on its 100-element fault, mu = 0.6, Sf = 0 (a degenerate
    LCP): ddc2d's Ds and shear traction of every element against the code's."""
    parm = np.loadtxt(RITZ / "parm.csv", delimiter=",")
    px, py = np.loadtxt(RITZ / "px.csv"), np.loadtxt(RITZ / "py.csv")
    reference = np.genfromtxt(RITZ / "reference_elements.csv", delimiter=",", names=True)
    model = ddc2d.Model(youngs_modulus=parm[1], poissons_ratio=parm[0], title="ritz2012")
    model.remote_stress(sxx=parm[2], syy=parm[3], sxy=parm[4])
    model.fracture(px, py, elements=1, condition="contact",
                   mu=np.loadtxt(RITZ / "mu.csv"), sf=np.loadtxt(RITZ / "sf.csv"),
                   name="fault")
    result = solve(model, "ritz")
    ds = result.elements["ds"]
    deviation = float(np.max(np.abs(ds - reference["Ds"]) / np.max(np.abs(reference["Ds"]))))
    traction = float(np.max(np.abs(result.elements["shear_traction"] - reference["Ss"])
                            / np.max(np.abs(reference["Ss"]))))
    assert traction < 1e-8, f"shear tractions differ by {traction} of the largest"
    k = int(np.argmax(np.abs(reference["Ds"])))
    row = record(id="paper-code-ds", benchmark=f"The paper's code, 100 elements, mu = 0.6, "
                 f"Sf = 0 ({PAPER})", reference="the paper's Matlab results "
                 "(tests/reference/ritz2012/)",
                 quantity="peak Ds [m] (every Ds and shear traction within 1e-8 of the "
                          "largest)",
                 value=float(ds[k]), reference_value=float(reference["Ds"][k]),
                 tolerance=1e-8, mesh="100 elements (the paper's)")
    assert row["passed"], row
    assert deviation < 1e-8, f"Ds differ by {deviation} of the largest"


#: The weak patch: half-length 1, patch |x| < c, strengths tau_r inside and tau_p outside.
C, MU, SN, SF_IN, SF_OUT, TAU = 0.4, 0.6, -10.0, 0.0, 6.0, 9.0
PATCH_LEVELS = (100, 200, 400)


def weak_patch(n):
    """n elements on |x| < 1, equal, with the patch's ends on element ends."""
    model = ddc2d.Model(youngs_modulus=E, poissons_ratio=NU, title="weak patch")
    model.remote_stress(syy=SN, sxy=TAU)
    outer, inner = 3 * n // 10, 4 * n // 10
    model.fracture([-1.0, -C, C, 1.0], [0.0, 0.0, 0.0, 0.0], elements=[outer, inner, outer],
                   condition="contact", mu=MU, sf=[SF_OUT, SF_IN, SF_OUT], name="fault")
    return model


def test_partly_sticking_fault(solve, record):
    """Slip spreads beyond the patch to a_s = c / cos(pi (tau - tau_r) / (2 P)) and sticks
    beyond; D(0) = 2 (1 - nu) P c / (pi G) ln((a_s + s_c) / (a_s - s_c)), P = tau_p - tau_r,
    s_c = sqrt(a_s^2 - c^2) (docs/theory/contact.md#checks-against-closed-forms)."""
    tau_r, tau_p = SF_IN + MU * abs(SN), SF_OUT + MU * abs(SN)
    p = tau_p - tau_r
    a_s = C / math.cos(math.pi * (TAU - tau_r) / (2 * p))
    s_c = math.sqrt(a_s**2 - C**2)
    peak = 2 * (1 - NU) * p * C / (math.pi * G) * math.log((a_s + s_c) / (a_s - s_c))
    results = [solve(weak_patch(n), f"patch{n}") for n in PATCH_LEVELS]
    assert all(np.max(np.abs(r.elements["ds"])) > 0.99 * peak for r in results)
    reference = "Partial slip on a fault with a weak patch (docs/theory/contact.md)"
    mesh = f"{PATCH_LEVELS[-1]} elements"
    # No observed order: the end of the slip zone moves by whole elements between levels.
    row = record(id="partial-stick-peak-slip", benchmark="Fault with a weak patch: partly "
                 "sticks", reference=reference, quantity="peak slip [m]",
                 value=float(np.max(np.abs(results[-1].elements["ds"]))),
                 reference_value=peak, tolerance=2e-3, mesh=mesh)
    assert row["passed"], row
    last = results[-1].elements
    slipping = last["state"] == 2
    assert np.all(last["state"][~slipping] == 1), "the rest sticks"
    edge = float(np.max(np.abs(np.concatenate([last["x_begin"][slipping],
                                                last["x_end"][slipping]]))))
    element = 2.0 / PATCH_LEVELS[-1]
    row = record(id="partial-stick-slip-zone", benchmark="Fault with a weak patch: partly "
                 "sticks", reference=f"a_s = c / cos(pi (tau - tau_r) / (2 (tau_p - tau_r))) "
                 f"({reference})", quantity="end of the slip zone [m] (within one element "
                 f"{element:g})", value=edge, reference_value=a_s, tolerance=element,
                 tolerance_kind="absolute", mesh=f"{PATCH_LEVELS[-1]} elements")
    assert row["passed"], row
