"""Axis, sign and unit conventions of certkit, written down once.

Every model and rule follows these; ``tests/test_conventions.py`` checks them.

Units
    SI inside everywhere: m, kg, s, N, rad, Pa, K. Quantities are converted from the aircraft file's
    units at the input boundary (:mod:`certkit.units`) and to display units only when a report is
    written. Angles are radians inside; "deg" appears only in names such as ``elevator_deflection_deg``.

Airplane (geometry) frame — used in the aircraft file and the vortex lattice
    Origin at the fuselage nose, X aft, Y toward the right wing, Z up (the AVL geometry frame).
    Fuselage stations, CG positions ("97.25 ft from the nose") and surface root positions are X values.

Body axes — used by the flight dynamics
    Origin at the centre of gravity, x forward, y right wing, z down. A point at airplane-frame
    (X, Y, Z) is at body (-(X - X_cg), Y, -(Z - Z_cg)).

Aerodynamic angles and rates
    alpha = atan(w/u), beta = asin(v/V) (wind from the right is positive beta).
    p, q, r body rates; non-dimensional p_hat = p b / 2V, q_hat = q c / 2V, r_hat = r b / 2V
    (the AVL normalisation, so derivatives compare directly with AVL output).

Coefficients
    CL, CD: lift and drag, stability axes (perpendicular / parallel to the relative wind in the
    plane of symmetry). CY: side force, +y. Cl, Cm, Cn: rolling (right wing down +), pitching
    (nose up +) and yawing (nose right +) moments about the moment reference point, normalised by
    q S b, q S c, q S b. Derivatives are per radian (rates per unit p_hat, q_hat, r_hat).

Drag axis
    certkit's drag coefficient CD acts along the stability x axis (the relative wind projected on the plane of
    symmetry) and the side force CY along body y: with sideslip the drag has no side component. JSBSim's DRAG
    acts along the relative wind itself (wind axes), so with sideslip β it adds a side force −D sin β. In trimmed
    flight D ≈ T cos α, so JSBSim's sideslip equation carries an extra damping term −T cos α/(m V) in Y_v/m: about
    half of the Dutch-roll damping difference between certkit and JSBSim for the B747 and 737 imported from JSBSim
    (1.1 % and 0.6 % of the real part; tests/dynamics/test_jsbsim_import.py).
    ``certkit derivatives`` states it in its output (DRAG_AXIS).

Control surfaces — a positive deflection produces a negative moment (Etkin & Reid)
    elevator: trailing edge down positive (nose-down pitching moment).
    stabilizer (movable horizontal stabiliser): leading edge up positive (airplane nose-down trim), the whole tail
    turning about the pitch axis; the model's control is the deflection from ``horizontal_tail.incidence``, the
    trims report the incidence.
    aileron: right aileron trailing edge down positive, left one up (left-wing-down rolling moment).
    rudder: trailing edge left positive (nose-left yawing moment).
    flaps, slats: deployed positive.
    This holds for aircraft files (the lattice builds each surface's deflection in this sense). An AVL geometry
    file read by ``certkit derivatives`` keeps AVL's own signs (CONTROL_SIGNS).

Speeds
    A speed in the aircraft file states its kind: EAS, CAS or TAS. Inside, speeds are m/s and a
    condition records which kind it is; :mod:`certkit.atmosphere` converts between kinds.

Load factor
    n_z = L / W positive up in level flight (1 g), i.e. minus the body-z specific force over g.
"""

#: the drag-axis convention in one line, for outputs
DRAG_AXIS = (
    "CD along the stability x axis (relative wind projected on the plane of symmetry; no side component "
    "with sideslip); JSBSim's drag acts along the relative wind (−D sin β side force)"
)

#: the control sign convention of each input kind of ``certkit derivatives``
CONTROL_SIGNS = {
    "aircraft": "certkit's (Etkin & Reid): a positive deflection gives a negative moment — elevator trailing edge "
    "down, right aileron trailing edge down, rudder trailing edge left",
    "avl": "the AVL file's own: a positive deflection turns the surface right-handedly about its CONTROL hinge "
    "vector (SgnDup on the mirrored half), as AVL prints them (certkit per radian, AVL per degree)",
}

#: what ``certkit derivatives`` calls the induced drag
INDUCED_DRAG = (
    "Trefftz-plane induced drag (AVL's CDff); AVL's near-field CDi (surface-force integration) is not "
    "computed and differs by a few per cent"
)
