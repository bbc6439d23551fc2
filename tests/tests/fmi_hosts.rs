//! An exported FMU as other hosts drive it, through the C entry points: call
//! order and argument checks, direct feedthrough between steps, and hosts that
//! accumulate time in floating point (issue 11: ecos passes `t += h`).

use slender_fmi::ffi::*;
use slender_fmi::import::file_uri;
use slender_fmi::model_description::ModelDescription;
use slender_tests::fmu;
use std::ffi::CString;
use std::path::Path;

/// A live instance of an exported unit (freed on drop) and its model description.
struct Instance {
    c: fmi2Component,
    md: ModelDescription,
    _callbacks: Box<fmi2CallbackFunctions>,
}

impl Instance {
    /// Exports `unit` of the example `scene` into `dir` and instantiates it.
    fn new(scene: &str, unit: &str, dir: &Path) -> Instance {
        let file = fmu::export(scene, unit, dir);
        let folder = dir.join(format!("{unit}-unzipped"));
        zip::ZipArchive::new(std::fs::File::open(&file).unwrap())
            .unwrap()
            .extract(&folder)
            .unwrap();
        let xml = std::fs::read_to_string(folder.join("modelDescription.xml")).unwrap();
        let md = ModelDescription::parse(&xml).unwrap();
        let uri = CString::new(file_uri(&folder.join("resources"))).unwrap();
        let guid = CString::new(md.guid.clone()).unwrap();
        let name = CString::new(unit).unwrap();
        let callbacks = Box::new(fmi2CallbackFunctions {
            logger: None,
            allocate_memory: None,
            free_memory: None,
            step_finished: None,
            component_environment: std::ptr::null_mut(),
        });
        // SAFETY: valid C strings and callbacks that outlive the instance.
        let c = unsafe {
            slender_fmu::fmi2Instantiate(
                name.as_ptr(),
                FMI2_CO_SIMULATION,
                guid.as_ptr(),
                uri.as_ptr(),
                &*callbacks,
                0,
                0,
            )
        };
        assert!(!c.is_null());
        Instance {
            c,
            md,
            _callbacks: callbacks,
        }
    }

    fn vr(&self, name: &str) -> u32 {
        self.md
            .variables
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("no variable {name}"))
            .value_reference
    }

    fn get(&self, name: &str) -> f64 {
        let mut value = f64::NAN;
        // SAFETY: one reference, one value.
        let status = unsafe { slender_fmu::fmi2GetReal(self.c, &self.vr(name), 1, &mut value) };
        assert_eq!(status, FMI2_OK, "get {name}");
        value
    }

    fn set(&self, name: &str, value: f64) -> fmi2Status {
        // SAFETY: one reference, one value.
        unsafe { slender_fmu::fmi2SetReal(self.c, &self.vr(name), 1, &value) }
    }

    fn start(&self) {
        // SAFETY: FMI calls on a live instance.
        unsafe {
            assert_eq!(
                slender_fmu::fmi2SetupExperiment(self.c, 0, 0.0, 0.0, 0, 0.0),
                FMI2_OK
            );
            assert_eq!(slender_fmu::fmi2EnterInitializationMode(self.c), FMI2_OK);
            assert_eq!(slender_fmu::fmi2ExitInitializationMode(self.c), FMI2_OK);
        }
    }

    fn step(&self, t: f64, h: f64) -> fmi2Status {
        // SAFETY: FMI call on a live instance.
        unsafe { slender_fmu::fmi2DoStep(self.c, t, h, 0) }
    }
}

impl Drop for Instance {
    fn drop(&mut self) {
        // SAFETY: the instance is live and freed once.
        unsafe {
            slender_fmu::fmi2Terminate(self.c);
            slender_fmu::fmi2FreeInstance(self.c);
        }
    }
}

#[test]
fn a_live_instance_refuses_unknown_references_wrong_types_and_late_parameters() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = Instance::new("examples/b1_two_masses.toml", "left", dir.path());
    let c = fmu.c;
    // SAFETY: FMI calls on a live instance with valid arrays; the point is what
    // they refuse.
    unsafe {
        let mut value = 0.0;
        assert_eq!(
            slender_fmu::fmi2GetReal(c, &9999, 1, &mut value),
            FMI2_ERROR
        );
        // A Real parameter set as an Integer.
        let mass = fmu.vr("mass");
        assert_eq!(slender_fmu::fmi2SetInteger(c, &mass, 1, &2), FMI2_ERROR);
    }
    // Outputs cannot be set.
    assert_eq!(fmu.set("displacement", 1.0), FMI2_ERROR);
    // A parameter set before initialisation takes effect: twice the mass, a lower
    // frequency, so less displacement lost after 0.1 s.
    assert_eq!(fmu.set("mass", 2.0), FMI2_OK);
    fmu.start();
    for k in 0..10 {
        assert_eq!(fmu.step(0.01 * k as f64, 0.01), FMI2_OK);
    }
    let value = fmu.get("displacement");
    let (k_total, m) = (39.47841760435743 + 157.91367041742973, 2.0_f64);
    let exact = (0.1 * (k_total / m).sqrt()).cos();
    assert!((value - exact).abs() < 1e-3, "{value} vs {exact}");
    // Fixed parameters cannot change once initialised; a step must start at the
    // FMU's own time.
    assert_eq!(fmu.set("mass", 3.0), FMI2_ERROR);
    assert_eq!(fmu.step(5.0, 0.01), FMI2_ERROR);
    assert_eq!(fmu.step(0.1, -0.01), FMI2_ERROR);
}

#[test]
fn outputs_with_direct_feedthrough_follow_inputs_set_between_steps() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = Instance::new("examples/b1_two_masses.toml", "left", dir.path());
    let (kc, dc) = (157.91367041742973, 0.0);
    // coupling_force = kc (x - x_in) + dc (v - v_in), at the communication point.
    let expected = |fmu: &Instance, x_in: f64, v_in: f64| {
        kc * (fmu.get("displacement") - x_in) + dc * (fmu.get("velocity") - v_in)
    };
    fmu.start();
    for (k, x_in) in [0.02, -0.05, 0.1].into_iter().enumerate() {
        assert_eq!(fmu.set("coupling_displacement", x_in), FMI2_OK);
        assert_eq!(fmu.set("coupling_velocity", 0.0), FMI2_OK);
        let force = fmu.get("coupling_force");
        let want = expected(&fmu, x_in, 0.0);
        assert!(
            (force - want).abs() <= 1e-12 * want.abs().max(1.0),
            "step {k}: coupling_force {force}, expected {want} for the input just set"
        );
        assert_eq!(fmu.step(0.01 * k as f64, 0.01), FMI2_OK);
    }
}

#[test]
fn a_host_accumulating_time_in_floating_point_runs_1e7_steps_and_a_repeat_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let drifting = Instance::new("examples/b1_two_masses.toml", "left", dir.path());
    let exact = Instance::new("examples/b1_two_masses.toml", "right", dir.path());
    drifting.start();
    exact.start();
    let h = 1e-3;
    let mut t = 0.0_f64;
    let mut worst_drift = 0.0_f64;
    for k in 0..10_000_000_u64 {
        assert_eq!(drifting.step(t, h), FMI2_OK, "step {k} at t = {t}");
        t += h;
        worst_drift = worst_drift.max((t - (k + 1) as f64 * h).abs());
    }
    println!("float-accumulated time drifted by up to {worst_drift:.3e} s over 1e7 steps");
    assert!(
        worst_drift > 1e-6,
        "the host did not drift: the test tests nothing"
    );
    // The FMU kept its own exact time: a repeat of the last step without a restored
    // state is refused, and the next step at its exact time is accepted.
    assert_eq!(drifting.step(t - h, h), FMI2_ERROR);
    assert_eq!(drifting.step(1e4, h), FMI2_OK);
    // A host with exact times stays accepted too.
    for k in 0..10 {
        assert_eq!(exact.step(k as f64 * h, h), FMI2_OK);
    }
}
