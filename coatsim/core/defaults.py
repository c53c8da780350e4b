"""Every default a user can change, in one place: the library's signatures, the command line and
the scenario schema all take their defaults from here, so they cannot disagree."""

from __future__ import annotations

#: Tolerance σ of the segmentation, mm (largest two-sided deviation from the input curve).
TOLERANCE_MM = 0.1
#: The tool axis a controller interpolates stays this close to the surface normal along a 3-D pass, deg.
ANGLE_TOL_DEG = 2.0
#: A turn within a short length sharper than this is a true corner (the tool stops there), deg.
CORNER_DEG = 20.0
#: Where a 3-D fit's arcs may lie: any plane, or only planes normal to X, Y or Z (G-code G17/G18/G19).
ARC_PLANES = "any"
#: Programmed tool speed, mm/s (plasma spraying runs at 300–1000 mm/s).
SPEED_MM_S = 500.0
#: Blend radius of the controller at a corner between blended moves (AS ACCURACY), mm.
ACCURACY_MM = 1.0
#: Tangent run-in before and run-out after a curve, mm: the gun reaches its speed before the curve.
LEAD_IN_MM = 30.0
LEAD_OUT_MM = 30.0
#: Approach and departure along the tool axis, and the travel clearance between contours, mm.
APPROACH_MM = 50.0
#: Distance of the tool centre point from the surface along its normal, mm.
STANDOFF_MM = 100.0
#: The controller output that opens the gun, and the largest signal number a cell has.
GUN_SIGNAL = 1
MAX_SIGNAL = 9999
#: Workpiece frame in the robot base frame: x, y, z (mm), O, A, T (deg): a horizontal plate in
#: front of a ~1.4 m reach arm, normal up.
WORKPIECE_FRAME = (700.0, 0.0, 200.0, 0.0, 0.0, 0.0)
#: The gun's tool centre point in the flange frame, x, y, z (mm), O, A, T (deg): the shipped
#: plasma gun's TCP 250 mm from the flange.
GUN_TOOL = (0.0, 0.0, 250.0, 0.0, 0.0, 0.0)
#: Spray footprint and deposited volume rate of the shipped gun.
FOOTPRINT = "gaussian:sigma=5"
FLOW_MM3_S = 40.0
#: Cartesian sampling step of the inverse kinematics along a path, mm.
STEP_MM = 1.0
#: Deposition efficiency by spray angle (coatsim.spray.efficiency): none, every particle that lands sticks.
EFFICIENCY = "none"
#: Shadows (coatsim.spray.visibility): auto, ray-cast where the part can shadow itself.
SHADOWS = "auto"
#: The specification band: thickness within this many per cent of the target.
TOLERANCE_PCT = 10.0
#: Passes on a 3-D part (coatsim plan): the pattern and spraying order; the pass spacing in standard
#: deviations of the footprint (overlap ripple 2.9 %); the lead-in and lead-out past the region's
#: edge in standard deviations (the footprint clears the edge); faces within this angle of the
#: gun's side are coated; the band kept free along the region's border, mm; the region's edges
#: are refined to at most the spacing over this; the unit a mesh file is read in.
PLAN_PATTERN = "raster"
PLAN_ORDER = "serpentine"
PLAN_SPACING_SIGMAS = 2.0
PLAN_MARGIN_SIGMAS = 3.0
PLAN_FACING_DEG = 80.0
PLAN_EDGE_BAND_MM = 0.0
PLAN_EDGES_PER_SPACING = 4.0
PLAN_UNITS = "auto"
#: Where a scenario's programs of 3-D passes hold the programmed speed: on the spray spot's trace
#: (the thickness follows the spot's speed; ``coatsim program --speed-on`` keeps tcp for programs).
SCENARIO_SPEED_ON = "trace"
