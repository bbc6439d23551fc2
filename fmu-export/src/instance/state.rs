//! FMU state: `fmi2GetFMUstate` / `fmi2SetFMUstate` copies of the instance, and
//! their serialised form (the unit's driver state, fingerprinted to the unit's
//! configuration).

use super::*;

/// What `fmi2GetFMUstate` copies.
pub(super) struct SavedInstance {
    slot: DriverSlot,
    phase: Phase,
    time: Time,
    inputs: Vec<f64>,
    outputs: Vec<f64>,
}

/// The serialised form of a [`SavedInstance`].
#[derive(Serialize, Deserialize)]
struct SerializedInstance {
    magic: String,
    /// The configuration's fingerprint: a state only fits the same unit built
    /// with the same parameters.
    fingerprint: String,
    phase: Phase,
    time_ns: i64,
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    unit: Vec<u8>,
}

const MAGIC: &str = "slender-fmu-state-2";

impl Instance {
    pub(crate) fn get_state(&mut self, handle: &mut fmi2FMUstate) -> Result<fmi2Status, String> {
        if self.phase == Phase::Initialization {
            self.settle()?;
        }
        let unit = self
            .unit
            .as_ref()
            .ok_or("no state before fmi2EnterInitializationMode")?;
        if handle.is_null() {
            let saved = SavedInstance {
                slot: DriverSlot::new(),
                phase: self.phase,
                time: self.time,
                inputs: Vec::new(),
                outputs: Vec::new(),
            };
            *handle = Box::into_raw(Box::new(saved)).cast::<c_void>();
        }
        // SAFETY: non-null handles are ours (Box<SavedInstance>).
        let saved = unsafe { &mut *handle.cast::<SavedInstance>() };
        unit.save(&mut saved.slot).map_err(|e| e.to_string())?;
        saved.phase = self.phase;
        saved.time = self.time;
        saved.inputs.clone_from(&self.inputs);
        saved.outputs.clone_from(&self.outputs);
        Ok(FMI2_OK)
    }

    pub(crate) fn set_state(&mut self, handle: fmi2FMUstate) -> Result<fmi2Status, String> {
        self.generation += 1;
        if handle.is_null() {
            return Err("null state".into());
        }
        // SAFETY: non-null handles are ours (Box<SavedInstance>).
        let saved = unsafe { &*handle.cast::<SavedInstance>() };
        let unit = self.unit()?;
        unit.restore(&saved.slot).map_err(|e| e.to_string())?;
        self.phase = saved.phase;
        self.time = saved.time;
        self.inputs.clone_from(&saved.inputs);
        self.outputs.clone_from(&saved.outputs);
        self.reinitialize = false;
        self.inputs_changed = false;
        self.ramped.iter_mut().for_each(|r| *r = false);
        Ok(FMI2_OK)
    }

    pub(crate) fn serialize(&self, handle: fmi2FMUstate) -> Result<Vec<u8>, String> {
        if handle.is_null() {
            return Err("null state".into());
        }
        // SAFETY: non-null handles are ours (Box<SavedInstance>).
        let saved = unsafe { &*handle.cast::<SavedInstance>() };
        let state = SerializedInstance {
            magic: MAGIC.into(),
            fingerprint: self.config.fingerprint(),
            phase: saved.phase,
            time_ns: saved.time.as_nanos(),
            inputs: saved.inputs.clone(),
            outputs: saved.outputs.clone(),
            unit: saved.slot.to_bytes().map_err(|e| e.to_string())?,
        };
        postcard::to_stdvec(&state).map_err(|e| format!("serialising the state: {e}"))
    }

    pub(crate) fn deserialize(
        &self,
        bytes: &[u8],
        handle: &mut fmi2FMUstate,
    ) -> Result<fmi2Status, String> {
        let state: SerializedInstance = postcard::from_bytes(bytes)
            .map_err(|e| format!("the bytes are not a serialised slender FMU state ({e})"))?;
        if state.magic != MAGIC {
            return Err(format!(
                "state format `{}`: expected `{MAGIC}`",
                state.magic
            ));
        }
        if state.fingerprint != self.config.fingerprint() {
            return Err("the state belongs to another unit or other parameters".into());
        }
        if state.inputs.len() != self.n_in() || state.outputs.len() != self.n_out() {
            return Err("the state's input or output count does not match the unit".into());
        }
        let saved = SavedInstance {
            slot: DriverSlot::from_bytes(&state.unit).map_err(|e| e.to_string())?,
            phase: state.phase,
            time: Time::from_nanos(state.time_ns),
            inputs: state.inputs,
            outputs: state.outputs,
        };
        free_state(*handle);
        *handle = Box::into_raw(Box::new(saved)).cast::<c_void>();
        Ok(FMI2_OK)
    }
}
