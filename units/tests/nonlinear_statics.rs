//! Static verification of the nonlinear section (issue 12, groups 1 and 2):
//! the large-deflection cantilever against the elastica (Mattiasson 1981), a tip
//! moment rolling a cantilever into a circle, and the elastic catenary against
//! Irvine's closed form.

use crate::support::published;
use slender_units::nonlinear::{NonlinearParams, NonlinearSection};
use slender_units::{Driver, Time};

/// A section from TOML parameters, initialised (static start).
fn solved(text: &str) -> Driver<NonlinearSection> {
    let params: NonlinearParams = toml::from_str(text).expect("parameters parse");
    let mut driver = Driver::new(NonlinearSection::new(params).expect("valid parameters"));
    driver.initialize(Time::ZERO).expect("static solve");
    driver
}

fn column(table: &toml::Table, key: &str) -> Vec<f64> {
    table[key]
        .as_array()
        .expect("array")
        .iter()
        .map(|v| {
            v.as_float()
                .or_else(|| v.as_integer().map(|i| i as f64))
                .expect("number")
        })
        .collect()
}

fn cantilever(formulation: &str, elements: usize, end: &str, steps: u32) -> String {
    format!(
        r#"
formulation = "{formulation}"
static_start = true
load_steps = {steps}
segments = [{{ length = 10.0, elements = {elements}, axial_stiffness = 1e12, bending_stiffness = 1e4, mass_per_length = 1.0 }}]
ends.start = {{ kind = "fixed" }}
ends.end = {end}
"#
    )
}

#[test]
fn a_cantilever_under_a_tip_load_follows_the_elastica_within_0_1_percent() {
    let table = published()["elastica_cantilever"]
        .as_table()
        .expect("table")
        .clone();
    let (k, horizontal, vertical, rotation) = (
        column(&table, "load_parameter"),
        column(&table, "horizontal"),
        column(&table, "vertical"),
        column(&table, "rotation"),
    );
    let (l, ei) = (10.0, 1e4);
    for i in 0..k.len() {
        let p = k[i] * ei / (l * l);
        let end = format!("{{ z = {{ force = {} }} }}", -p);
        let section = solved(&cantilever("corotational", 40, &end, 10));
        let q = section.displacements();
        let tip = q.len() - 3;
        let (u, w, th) = (-q[tip] / l, -q[tip + 1] / l, -q[tip + 2]);
        for (what, got, want) in [
            ("u", u, horizontal[i]),
            ("w", w, vertical[i]),
            ("theta", th, rotation[i]),
        ] {
            assert!(
                ((got - want) / want).abs() < 1e-3,
                "PL^2/EI = {}: {what} = {got:.6}, elastica {want}",
                k[i]
            );
        }
    }
}

#[test]
fn a_tip_moment_of_2_pi_ei_over_l_rolls_a_cantilever_into_a_circle() {
    let (l, ei) = (10.0, 1e4);
    let moment = 2.0 * std::f64::consts::PI * ei / l;
    let end = format!("{{ rotation = {{ force = {moment} }} }}");
    let section = solved(&cantilever("corotational", 40, &end, 20));
    let q = section.displacements();
    let tip = q.len() - 3;
    assert!(
        (q[tip + 2] - 2.0 * std::f64::consts::PI).abs() < 1e-9,
        "tip rotation {}",
        q[tip + 2]
    );
    // Under a pure end moment every element turns by 2 theta = 2 pi / n with no
    // axial force, so its shallow-arch strain makes the chord l (1 - theta^2 / 6),
    // the chord of the circular arc to O(theta^4): the nodes are the vertices of a
    // regular n-gon of that side, closing on the root, on a circle tangent at the
    // root whose radius is L / (2 pi) to O(theta^4).
    let n = 40.0;
    let theta = std::f64::consts::PI / n;
    let side = l / n * (1.0 - theta * theta / 6.0);
    let r = side / (2.0 * theta.sin());
    assert!(
        (r - l / (2.0 * std::f64::consts::PI)).abs() < 1e-5 * r,
        "radius {r}"
    );
    let positions = section.positions();
    for (j, p) in positions.iter().enumerate() {
        let d = p[0].hypot(p[1] - r);
        assert!(
            (d - r).abs() < 1e-9 * l,
            "node {j} at distance {d} from the centre, radius {r}"
        );
    }
    let (root, end) = (positions[0], positions[positions.len() - 1]);
    assert!(
        (end[0] - root[0]).hypot(end[1] - root[1]) < 1e-9 * l,
        "the polygon closes"
    );
}

/// Irvine's elastic catenary hanging from (0, 0) to (span, rise): horizontal force
/// H and vertical force V at the lower end, by Newton on the closed form.
struct Irvine {
    w: f64,
    ea: f64,
    h: f64,
    v: f64,
}

impl Irvine {
    fn position(&self, s: f64) -> [f64; 2] {
        let (h, v, w) = (self.h, self.v, self.w);
        let x = h * s / self.ea + h / w * (((v + w * s) / h).asinh() - (v / h).asinh());
        let z = w * s * s / (2.0 * self.ea)
            + v * s / self.ea
            + h / w * ((1.0 + ((v + w * s) / h).powi(2)).sqrt() - (1.0 + (v / h).powi(2)).sqrt());
        [x, z]
    }

    fn tension(&self, s: f64) -> f64 {
        self.h.hypot(self.v + self.w * s)
    }

    fn solve(w: f64, ea: f64, length: f64, target: [f64; 2]) -> Irvine {
        let mut c = Irvine {
            w,
            ea,
            h: w * length,
            v: -0.2 * w * length,
        };
        for _ in 0..100 {
            let f0 = c.position(length);
            let r = [f0[0] - target[0], f0[1] - target[1]];
            if r[0].hypot(r[1]) < 1e-12 * length {
                return c;
            }
            let mut j = [[0.0; 2]; 2];
            for (k, d) in [(0, 1e-6 * c.h), (1, 1e-6 * c.h)] {
                let mut p = Irvine { ..c };
                if k == 0 {
                    p.h += d
                } else {
                    p.v += d
                }
                let f = p.position(length);
                j[0][k] = (f[0] - f0[0]) / d;
                j[1][k] = (f[1] - f0[1]) / d;
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            let (dh, dv) = (
                (j[1][1] * r[0] - j[0][1] * r[1]) / det,
                (-j[1][0] * r[0] + j[0][0] * r[1]) / det,
            );
            // Damped so that H stays positive (the other branch is unphysical).
            let damping = if dh > 0.5 * c.h { 0.5 * c.h / dh } else { 1.0 };
            c.h -= damping * dh;
            c.v -= damping * dv;
        }
        panic!("Irvine's equations did not converge");
    }
}

#[test]
fn a_hanging_line_matches_irvines_elastic_catenary_within_1e_4() {
    // A chain-like line: 300 m, 1000 N/m in water, EA = 1e8 N, EI -> 0, between
    // (0, 0) and (250, 120).
    let (length, w, ea) = (300.0, 1000.0, 1e8);
    let target: [f64; 2] = [250.0, 120.0];
    let angle = target[1].atan2(target[0]).to_degrees();
    let (ex, ez) = (
        target[0] - length * angle.to_radians().cos(),
        target[1] - length * angle.to_radians().sin(),
    );
    let text = format!(
        r#"
static_start = true
start_shape = "catenary"
segments = [{{ length = {length}, angle_deg = {angle}, elements = 100, axial_stiffness = {ea}, bending_stiffness = 1.0, mass_per_length = 100.0, submerged_weight = {w} }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ kind = "pinned", x = {{ displacement = {ex} }}, z = {{ displacement = {ez} }} }}
"#
    );
    let section = solved(&text);
    let exact = Irvine::solve(w, ea, length, target);
    let positions = section.positions();
    let arc = &section.model().arc;
    for (j, p) in positions.iter().enumerate() {
        let e = exact.position(arc[j]);
        let err = (p[0] - e[0]).hypot(p[1] - e[1]);
        assert!(err < 1e-4 * length, "node {j}: {p:?} against {e:?}");
    }
    let r = section.reactions();
    let n = r.len();
    let bottom = r[0].hypot(r[1]);
    let top = r[n - 3].hypot(r[n - 2]);
    for (what, got, want) in [
        ("bottom", bottom, exact.tension(0.0)),
        ("top", top, exact.tension(length)),
    ] {
        assert!(
            ((got - want) / want).abs() < 1e-4,
            "{what} tension {got:.2} N, Irvine {want:.2} N"
        );
    }
}

/// Seed 000's polyester line (Table 1, 2.5 MN at 50 deg from the vertical, current
/// 0 to 0.5 m/s) as a nonlinear section with negligible EI against the `cable`
/// unit (both 80 elements, both with weight and current drag): the top position,
/// the top angle and the angle at the truncation point (z = 960 m, paper 39.2 deg,
/// cable unit 39.25 deg).
#[test]
fn the_polyester_line_matches_the_cable_unit_at_the_top_and_the_truncation_point() {
    use slender_units::cable::{Cable, CableParams, Effects};
    let line = CableParams::seed000_polyester(80);
    let a = 50f64.to_radians();
    let top_force = [2.5e6 * a.sin(), 2.5e6 * a.cos()];
    let mut cable = Driver::new(Cable::new(line.clone(), Effects::all()).expect("cable"));
    cable
        .set_inputs(&[top_force[0], top_force[1], 0.0, 0.0])
        .expect("inputs");
    cable.initialize(Time::ZERO).expect("cable statics");
    let reference = cable
        .static_state()
        .expect("static state")
        .positions
        .clone();
    let text = format!(
        r#"
static_start = true
segments = [{{ length = {length}, angle_deg = 39.4, elements = 80, axial_stiffness = {ea}, bending_stiffness = 1.0e2, mass_per_length = {m}, submerged_weight = {w}, diameter = {d}, drag_normal = {cd}, added_mass_normal = 1.0 }}]
ends.start = {{ kind = "pinned" }}
ends.end = {{ x = {{ force = {fx} }}, z = {{ force = {fz} }} }}
current = {{ z = [0.0, 1200.0], velocity = [0.0, 0.5] }}
"#,
        length = line.length,
        ea = line.axial_stiffness(),
        m = line.mass_per_length,
        w = line.submerged_weight,
        d = line.diameter,
        cd = line.drag_normal,
        fx = top_force[0],
        fz = top_force[1],
    );
    let section = solved(&text);
    let ours = section.positions();
    let angle = |p: &[[f64; 2]], i: usize, j: usize| {
        (p[j][1] - p[i][1]).atan2(p[j][0] - p[i][0]).to_degrees()
    };
    // The truncation point: where the line crosses 80 % of the depth.
    let crossing = |p: &[[f64; 2]]| {
        p.windows(2)
            .position(|w| w[0][1] <= 960.0 && w[1][1] > 960.0)
            .expect("crosses z = 960 m")
    };
    let (k, kc) = (crossing(&ours), crossing(&reference));
    assert_eq!(k, kc, "the same element crosses z = 960 m");
    for (what, got, want) in [
        ("top x", ours[80][0], reference[80][0]),
        ("top z", ours[80][1], reference[80][1]),
        ("node 64 x", ours[64][0], reference[64][0]),
    ] {
        println!("{what}: {got:.3} m, cable unit {want:.3} m");
        assert!(
            (got - want).abs() < 1e-3 * line.length,
            "{what}: {got} m against {want} m"
        );
    }
    let top = (angle(&ours, 79, 80), angle(&reference, 79, 80));
    let truncation = (angle(&ours, k, k + 1), angle(&reference, k, k + 1));
    println!(
        "top angle {:.3} deg (cable {:.3}); truncation-point angle {:.3} deg (cable {:.3}, paper 39.2)",
        top.0, top.1, truncation.0, truncation.1
    );
    assert!((top.0 - top.1).abs() < 0.01, "top angle {top:?}");
    assert!(
        (truncation.0 - truncation.1).abs() < 0.05,
        "truncation angle {truncation:?}"
    );
    assert!(
        (truncation.0 - 39.25).abs() < 0.1,
        "truncation angle {} deg",
        truncation.0
    );
}

#[test]
fn the_internal_force_at_a_node_is_the_weight_hanging_below_it() {
    // 30 m hanging from a pin, 300 N/m in water, 30 elements: at a node the mean
    // of its two elements' forces is what a cut there transmits, the weight of
    // the 30 - s metres below; inside an element, the element's own force.
    let section = solved(
        r#"
static_start = true
start = [0.0, 0.0]
segments = [{ length = 30.0, angle_deg = -90.0, elements = 30, axial_stiffness = 1e10, bending_stiffness = 1e3, mass_per_length = 50.0, submerged_weight = 300.0 }]
ends.start = { kind = "pinned" }
stations = [10.0, 20.0, 10.5]
"#,
    );
    let names: Vec<String> = section
        .description()
        .outputs
        .iter()
        .map(|p| p.name.clone())
        .collect();
    let mut out = vec![0.0; names.len()];
    section.outputs(&mut out).unwrap();
    let at = |name: &str| out[names.iter().position(|n| n == name).unwrap()];
    for (i, s) in [(1, 10.0), (2, 20.0)] {
        let force = at(&format!("force_{i}"));
        assert!((force - 300.0 * (30.0 - s)).abs() < 1e-6 * force, "{force}");
        // The element's tension differs by half an element's weight.
        assert!((at(&format!("tension_{i}")) - force).abs() > 100.0);
    }
    // Inside element 10 (10-11 m): its own force, 300 (30 - 10.5) N.
    assert!((at("force_3") - 300.0 * 19.5).abs() < 1e-6 * 5850.0);
}
