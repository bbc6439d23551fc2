//! One contract test over every unit kind in the registry: byte-equal rollback
//! (outputs and serialised state after restore and repeat), no allocation on
//! rollback, refusal of wrong input counts, non-finite inputs and calls out of
//! order, and determinism (the same configuration gives the same bytes).
//!
//! Each kind is driven from a sample: a unit of an example scene (with the start
//! inputs its master settles on) or an inline parameter table. A kind added to the
//! registry without a sample fails `every_registry_kind_has_a_contract_sample`.

use slender_scene::export::ExportedUnit;
use slender_scene::kinds::KINDS;
use slender_tests::samples::{inputs_at, samples, start_inputs, started};
use slender_units::{Driver, DriverSlot, Time, UnitError};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Counts this thread's allocations (tests run on several threads).
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded to the system allocator with the caller's layout.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|c| c.set(c.get() + 1));
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

/// Steps once from `t` with `inputs`; the outputs' bits and the serialised state.
fn step_bits(driver: &mut Driver, t: Time, h: Time, inputs: &[f64]) -> (Vec<u64>, Vec<u8>) {
    driver.set_inputs(inputs).unwrap();
    driver.do_step(t, h).unwrap();
    let mut out = vec![0.0; driver.description().outputs.len()];
    driver.outputs(&mut out).unwrap();
    let mut slot = DriverSlot::new();
    driver.save(&mut slot).unwrap();
    let state = slot.to_bytes().unwrap();
    (out.iter().map(|v| v.to_bits()).collect(), state)
}

#[test]
fn every_registry_kind_has_a_contract_sample() {
    let dir = tempfile::tempdir().unwrap();
    let covered: Vec<&str> = samples(dir.path()).iter().map(|(k, _)| *k).collect();
    for kind in KINDS {
        assert!(
            covered.contains(&kind.name),
            "kind `{}` has no sample in the contract test",
            kind.name
        );
    }
    for (kind, config) in samples(dir.path()) {
        // A label names the kind, then a variant (`nonlinear linear`).
        assert_eq!(
            kind.split(' ').next(),
            Some(config.kind.as_str()),
            "sample for `{kind}` builds a `{}`",
            config.kind
        );
    }
}

#[test]
fn rollback_repeats_a_step_byte_for_byte_for_every_kind() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let (mut driver, start, h) = started(&config, 3);
        let t = h * 3;
        let mut slot = DriverSlot::new();
        driver.save(&mut slot).unwrap();
        let first = step_bits(&mut driver, t, h, &inputs_at(&start, 4));
        driver.restore(&slot).unwrap();
        step_bits(&mut driver, t, h, &inputs_at(&start, 9));
        driver.restore(&slot).unwrap();
        let repeat = step_bits(&mut driver, t, h, &inputs_at(&start, 4));
        assert_eq!(
            first.0, repeat.0,
            "{kind}: outputs of the repeated step differ"
        );
        // An FMU's serialised state is the FMU's own (a handle here): compared
        // through its outputs only.
        if kind != "fmu" {
            assert_eq!(first.1, repeat.1, "{kind}: state after the repeat differs");
        }
    }
}

#[test]
fn rollback_allocates_nothing_once_the_slot_is_filled() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let (mut driver, start, h) = started(&config, 3);
        let mut slot = DriverSlot::new();
        let mut cycle = |driver: &mut Driver, k: i64| {
            driver.save(&mut slot).unwrap();
            driver.set_inputs(&inputs_at(&start, 4 + k)).unwrap();
            driver.do_step(h * 3, h).unwrap();
            let before = allocations();
            driver.restore(&slot).unwrap();
            driver.save(&mut slot).unwrap();
            allocations() - before
        };
        // The first cycles size the slot and the unit's buffers.
        cycle(&mut driver, 0);
        cycle(&mut driver, 1);
        let counted = cycle(&mut driver, 2);
        assert_eq!(
            counted, 0,
            "{kind}: restore + save allocated {counted} times"
        );
    }
}

#[test]
fn wrong_input_counts_non_finite_inputs_and_calls_out_of_order_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let mut driver = config.driver().unwrap();
        let n = driver.description().inputs.len();
        let h = Time::from_secs(config.step).unwrap();
        let e = driver.do_step(Time::ZERO, h).unwrap_err();
        assert!(
            matches!(e, UnitError::State(_)),
            "{kind}: step before initialize: {e}"
        );
        let e = driver.restore(&DriverSlot::new()).unwrap_err();
        assert!(
            matches!(e, UnitError::State(_)),
            "{kind}: restore before save: {e}"
        );
        assert!(driver.modes(1).is_err(), "{kind}: modes before initialize");
        let e = driver.set_inputs(&vec![0.0; n + 1]).unwrap_err();
        assert!(
            matches!(e, UnitError::InputCount { expected, got } if expected == n && got == n + 1),
            "{kind}: {e}"
        );
        let mut out = vec![0.0; driver.description().outputs.len() + 1];
        assert!(driver.outputs(&mut out).is_err(), "{kind}: outputs buffer");
        if n > 0 {
            let mut bad = start_inputs(&config, &driver);
            bad[n - 1] = f64::NAN;
            let e = driver.set_inputs(&bad).unwrap_err();
            let port = &driver.description().inputs[n - 1].name;
            assert!(
                matches!(&e, UnitError::InvalidInput { port: p, .. } if p == port),
                "{kind}: {e}"
            );
        }
    }
}

#[test]
fn the_same_configuration_gives_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    for (kind, config) in samples(dir.path()) {
        let run = || {
            let (mut driver, start, h) = started(&config, 5);
            step_bits(&mut driver, h * 5, h, &inputs_at(&start, 6))
        };
        let (a, b) = (run(), run());
        assert_eq!(a.0, b.0, "{kind}: outputs differ between two builds");
        if kind != "fmu" {
            assert_eq!(a.1, b.1, "{kind}: states differ between two builds");
        }
    }
}
