"""The JSBSim Boeing 737 model (shipped with the jsbsim package) as certkit inputs.

The aerodynamic data are read from the model's XML (``aircraft/737/737.xml``) at the cruise
point of ``cruise_init.xml`` (30 000 ft, 750 ft/s): every coefficient there is linear in its
variables near cruise, so a StabilityDerivativeModel reproduces it exactly except where noted:
    * CL(α) table: the segment 0 ≤ α ≤ 0.23 rad (CL0 = 0.20, CLα = 1.0/0.23);
    * CD0(α) table: the segment 0 ≤ α ≤ 0.26 (CD_alpha); CDi = 0.043 CL² (k); CD from |δe| taken
      with the sign of the trim elevator; CDmach = 0 below M 0.79; gear, flap and spoiler
      increments at JSBSim's positions (its cruise_init leaves the gear down: CDgear = 0.015);
    * Clda(M), Cmde(M) tables: linear in Mach on [0, 2] → two Mach breakpoints, exact;
    * the moment derivatives are body-axis in JSBSim and are converted to stability axes at the
      trim α (D_s = R D_b Rᵀ for the rate derivatives), as the derivative model expects;
    * JSBSim's left aileron positive = left trailing edge down (right-wing-down roll); certkit's
      (Etkin) aileron is the opposite sign.
Mass, CG, inertia and gravity are read from the running JSBSim model after its trim (its inertia/ixz
property is the tensor element −∫xz dm, so certkit's Ixz is its negative); the thrust is
modelled as linear in throttle with JSBSim's trim thrust per engine at its trim throttle, at the
XML engine positions.
"""

from __future__ import annotations

import os
import xml.etree.ElementTree as ET

import numpy as np
from scipy.optimize import brentq

from certkit import atmosphere as isa
from certkit.models.aero.derivative_model import StabilityDerivativeModel
from certkit.models.aero.interface import AeroReference
from certkit.models.dynamics.eom import AircraftModel, Engine, inertia_tensor
from certkit.units import FT, LB, LBF

IN = 0.0254
SLUG = LB * 9.80665 / FT  # kg
SLUGFT2 = SLUG * FT * FT


def jsbsim_root() -> str:
    """JSBSim's data folder: the installed package's own (in chained dev venvs get_default_root_dir, which looks
    under sys.prefix, does not find it)."""
    import jsbsim

    here = os.path.dirname(jsbsim.__file__)
    return here if os.path.isdir(os.path.join(here, "aircraft")) else jsbsim.get_default_root_dir()


def jsbsim_cruise():
    """Run JSBSim's 737 from cruise_init, trim it (JSBSim's own full trim) and return the FDM."""
    import jsbsim

    fdm = jsbsim.FGFDMExec(jsbsim_root())
    fdm.set_debug_level(0)
    fdm.load_model("737")
    fdm.load_ic("cruise_init", True)
    fdm.run_ic()
    fdm["propulsion/set-running"] = -1
    fdm["simulation/do_simple_trim"] = 1
    return fdm


def _xml():
    return ET.parse(os.path.join(jsbsim_root(), "aircraft", "737", "737.xml")).getroot()


def _function(root, name):
    for f in root.iter("function"):
        if f.get("name") == f"aero/coefficient/{name}":
            return f
    raise KeyError(name)


def _value(root, name) -> float:
    return float(_function(root, name).find(".//value").text)


def _table(root, name) -> np.ndarray:
    rows = _function(root, name).find(".//tableData").text.split("\n")
    return np.array([[float(v) for v in r.split()] for r in rows if r.strip()])


def build_737(fdm, n: int = 1):
    """certkit AircraftModel of JSBSim's 737 about its trimmed cruise state; returns
    (model, V (m/s), h (m, ISA altitude with JSBSim's density))."""
    root = _xml()
    met = root.find("metrics")
    S = float(met.find("wingarea").text) * FT * FT
    b = float(met.find("wingspan").text) * FT
    c = float(met.find("chord").text) * FT
    arp = [loc for loc in met.findall("location") if loc.get("name") == "AERORP"][0]
    x_ref, z_ref = float(arp.find("x").text) * IN, float(arp.find("z").text) * IN
    a0 = fdm["aero/alpha-rad"]
    de0 = fdm["fcs/elevator-pos-rad"]

    cl_tab = _table(root, "CLalpha")
    i = np.searchsorted(cl_tab[:, 0], a0) - 1
    cla = (cl_tab[i + 1, 1] - cl_tab[i, 1]) / (cl_tab[i + 1, 0] - cl_tab[i, 0])
    cl0 = cl_tab[i, 1] - cla * cl_tab[i, 0]
    cd_tab = _table(root, "CD0")
    j = np.searchsorted(cd_tab[:, 0], a0) - 1
    cda = (cd_tab[j + 1, 1] - cd_tab[j, 1]) / (cd_tab[j + 1, 0] - cd_tab[j, 0])
    cd0 = cd_tab[j, 1] - cda * cd_tab[j, 0]
    # configuration increments at their JSBSim positions (cruise_init leaves the gear down)
    cd0 += (
        _value(root, "CDgear") * fdm["gear/gear-pos-norm"]
        + _value(root, "CDflap") * fdm["fcs/flap-pos-norm"]
        + _value(root, "CDsb") * fdm["fcs/speedbrake-pos-norm"]
        + _value(root, "CDsp") * fdm["fcs/spoiler-pos-norm"]
    )
    cl0 += _value(root, "dCLflap") * fdm["fcs/flap-pos-norm"]
    clda = _table(root, "Clda")  # vs Mach
    cmde = _table(root, "Cmde")
    mach = clda[:, 0]
    assert np.allclose(cmde[:, 0], mach)

    ca, sa = np.cos(a0), np.sin(a0)
    R = np.array([[ca, sa], [-sa, ca]])  # body (Cl, Cn) → stability (Cl, Cn)

    def vec(cl_b, cn_b):
        return R @ np.array([cl_b, cn_b], dtype=float)

    rate = R @ np.array([[_value(root, "Clp"), _value(root, "Clr")], [0.0, _value(root, "Cnr")]]) @ R.T
    beta = vec(_value(root, "Clb"), _value(root, "Cnb"))
    rud = vec(_value(root, "Cldr"), _value(root, "Cndr"))
    ail = np.array([vec(-v, 0.0) for v in clda[:, 1]])  # Etkin aileron = −JSBSim left aileron
    d = {
        "CL0": cl0,
        "CL_alpha": cla,
        "CL_elevator": _value(root, "CLde"),
        "CD0": cd0,
        "CD_alpha": cda,
        "k": _value(root, "CDi"),
        "CD_elevator": _value(root, "CDde") * np.sign(de0),
        "CY_beta": _value(root, "CYb"),
        "Cl_beta": beta[0],
        "Cn_beta": beta[1],
        "Cl_p": rate[0, 0],
        "Cl_r": rate[0, 1],
        "Cn_p": rate[1, 0],
        "Cn_r": rate[1, 1],
        "Cl_aileron": ail[:, 0],
        "Cn_aileron": ail[:, 1],
        "Cl_rudder": rud[0],
        "Cn_rudder": rud[1],
        "Cm_alpha": _value(root, "Cmalpha"),
        "Cm_elevator": cmde[:, 1],
        "Cm_q": _value(root, "Cmq"),
        "Cm_alphadot": _value(root, "Cmadot"),
    }
    aero = StabilityDerivativeModel(
        AeroReference(S, b, c, x_ref, z_ref), d, mach=mach, control_names=("elevator", "aileron", "rudder")
    )

    thr0 = fdm["fcs/throttle-pos-norm[0]"]
    engines = []
    for k, e in enumerate(root.find("propulsion").findall("engine")):
        loc = e.find("thruster").find("location")
        pos = [float(loc.find(a).text) * IN for a in ("x", "y", "z")]
        per_unit = fdm[f"propulsion/engine[{k}]/thrust-lbs"] * LBF / thr0
        engines.append(Engine(f"e{k + 1}", thrust=lambda thr, h, m, t=per_unit: thr * t, position=pos))
    J = inertia_tensor(
        fdm["inertia/ixx-slugs_ft2"] * SLUGFT2,
        fdm["inertia/iyy-slugs_ft2"] * SLUGFT2,
        fdm["inertia/izz-slugs_ft2"] * SLUGFT2,
        -fdm["inertia/ixz-slugs_ft2"] * SLUGFT2,
    )
    cg = (fdm["inertia/cg-x-in"] * IN, fdm["inertia/cg-y-in"] * IN, fdm["inertia/cg-z-in"] * IN)
    model = AircraftModel(
        aero,
        mass=fdm["inertia/mass-slugs"] * SLUG,
        cg=cg,
        inertia=J,
        engines=engines,
        g=fdm["accelerations/gravity-ft_sec2"] * FT,
        n=n,
    )
    rho = fdm["atmosphere/rho-slugs_ft3"] * SLUG / FT**3
    h = brentq(lambda hh: float(isa.density(hh)) - rho, 0.0, 15_000.0)
    return model, fdm["velocities/vt-fps"] * FT, h
