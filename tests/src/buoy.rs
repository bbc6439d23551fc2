//! A buoy's three chains in 50 m of water (the moored body's tests): its
//! fairleads, to end a `[mooring.body]`, and the lines with the recorded
//! signals, to follow it.

/// The buoy's three fairleads, 2 m from its centre line, 2 m down.
pub const FAIRLEADS: &str = r#"fairleads = [
    { name = "f1", position = [2.0, 0.0, -2.0] },
    { name = "f2", position = [-1.0, 1.732051, -2.0] },
    { name = "f3", position = [-1.0, -1.732051, -2.0] },
]
"#;

/// Three 120 m chains (500 N/m in water, EA 5e8 N) from anchors 100 m out,
/// and `[output]`: the buoy's surge and heave, line `l1`'s top tension.
pub const LINES: &str = r#"[mooring.line]
kind = "line3d"
length = 120.0
elements = 20
axial_stiffness = 5e8
mass_per_length = 60.0
submerged_weight = 500.0
diameter = 0.1
drag_normal = 1.2
added_mass_normal = 1.0
seabed = { depth = 50.0, stiffness = 3.0e6, damping = 3.0e5 }
[[mooring.lines]]
name = "l1"
fairlead = "f1"
anchor = [100.0, 0.0, -50.0]
[[mooring.lines]]
name = "l2"
fairlead = "f2"
anchor = [-50.0, 86.60254, -50.0]
[[mooring.lines]]
name = "l3"
fairlead = "f3"
anchor = [-50.0, -86.60254, -50.0]
[output]
signals = ["buoy.x", "buoy.z", "l1_full.end_tension"]
"#;
