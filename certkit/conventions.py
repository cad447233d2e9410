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

Control surfaces — a positive deflection produces a negative moment (Etkin & Reid)
    elevator: trailing edge down positive (nose-down pitching moment).
    aileron: right aileron trailing edge down positive, left one up (left-wing-down rolling moment).
    rudder: trailing edge left positive (nose-left yawing moment).
    flaps, slats: deployed positive.

Speeds
    A speed in the aircraft file states its kind: EAS, CAS or TAS. Inside, speeds are m/s and a
    condition records which kind it is; :mod:`certkit.atmosphere` converts between kinds.

Load factor
    n_z = L / W positive up in level flight (1 g), i.e. minus the body-z specific force over g.
"""
