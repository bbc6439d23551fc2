"""FMPy-side checks of slender's exported FMUs, run by tests/tests/fmi_python.rs.

    fmpy_checks.py validate FMU...            problems per FMU; exit code = their number
    fmpy_checks.py simulate FMU CSV STOP STEP [NAME=VALUE...]
    fmpy_checks.py state FMU                  FMU state save/restore/serialise round trips
                                              (FMI 2.0 or 3.0)
    fmpy_checks.py arrays FMU STOP STEP       a section's (nonlinear or cable) FMI 3.0 array
                                              outputs (x, z, tension) against its end and
                                              extreme outputs
    fmpy_checks.py resize FMU PARAMETER VALUE an FMI 3.0 section's mesh changed by an Int32
                                              parameter: arrays read at the sizes the FMU
                                              reports (n_nodes, n_elements), the sizes set
                                              before initialisation (a wrong one refused),
                                              and simulate_fmu with the description's sizes
    fmpy_checks.py derivatives FMU ROWS       slender's step derivative (the extension
                                              slenderGetStepDerivative) against central
                                              differences of fmi2DoStep for the outputs
                                              named in ROWS (comma-separated); the
                                              standard's fmi2GetDirectionalDerivative
                                              zero, or refused for feedthrough
"""

import ctypes
import math
import sys

from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.util import write_csv
from fmpy.validation import validate_fmu


def validate(paths):
    problems = 0
    for path in paths:
        found = validate_fmu(path)
        for p in found:
            print(f"{path}: {p}")
        problems += len(found)
    print(f"{len(paths)} FMUs, {problems} problems")
    return problems


def simulate(path, csv, stop, step, assignments):
    start_values = {}
    for a in assignments:
        name, value = a.split("=", 1)
        start_values[name] = float(value)
    result = simulate_fmu(path, stop_time=float(stop), output_interval=float(step),
                          start_values=start_values)
    write_csv(csv, result)
    return 0


class Slave3:
    """An FMI 3.0 slave behind FMU2Slave's method names (the calls `state` uses)."""

    def __init__(self, md, folder, name):
        self.s = FMU3Slave(guid=md.guid, unzipDirectory=folder,
                           modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
        self.s.instantiate()
        self.s.enterInitializationMode(startTime=0.0)
        self.s.exitInitializationMode()
        # How many values each array variable holds (its shape: FMPy takes a
        # size given by a structural parameter from that parameter's start).
        self.sizes = {v.valueReference: math.prod(v.shape)
                      for v in md.modelVariables if v.dimensions}

    def setReal(self, vr, values):
        self.s.setFloat64(vr, values)

    def getReal(self, vr):
        return self.s.getFloat64(vr, nValues=sum(self.sizes.get(r, 1) for r in vr))

    def doStep(self, t, h):
        self.s.doStep(t, h)

    def getFMUState(self):
        return self.s.getFMUState()

    def setFMUState(self, state):
        self.s.setFMUState(state)

    def freeFMUState(self, state):
        self.s.freeFMUState(state)

    def serializeFMUState(self, state):
        return self.s.serializeFMUState(state)

    def deSerializeFMUstate(self, blob):
        return self.s.deserializeFMUState(blob)

    def terminate(self):
        self.s.terminate()

    def freeInstance(self):
        self.s.freeInstance()


def instance(path, name):
    md = read_model_description(path)
    folder = extract(path)
    if md.fmiVersion == "3.0":
        return md, Slave3(md, folder, name)
    slave = FMU2Slave(guid=md.guid, unzipDirectory=folder,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName=name)
    slave.instantiate()
    slave.setupExperiment(startTime=0.0)
    slave.enterInitializationMode()
    slave.exitInitializationMode()
    return md, slave


def state(path):
    md, a = instance(path, "a")
    inputs = [v for v in md.modelVariables if v.causality == "input"]
    outputs = [v.valueReference for v in md.modelVariables if v.causality == "output"]
    in_refs = [v.valueReference for v in inputs]
    starts = [float(v.start) for v in inputs]
    h = 0.01

    def run(slave, first, steps):
        out = []
        for k in range(first, first + steps):
            t = k * h
            values = [s + 0.05 * (1 + abs(s)) * math.sin(0.7 * t + i) for i, s in enumerate(starts)]
            slave.setReal(in_refs, values)
            slave.doStep(t, h)
            out.append(slave.getReal(outputs))
        return out

    run(a, 0, 50)
    saved = a.getFMUState()
    blob = a.serializeFMUState(saved)
    reference = run(a, 50, 50)
    a.setFMUState(saved)
    again = run(a, 50, 50)
    a.freeFMUState(saved)
    restored = a.deSerializeFMUstate(blob)
    a.setFMUState(restored)
    from_bytes = run(a, 50, 50)
    md, b = instance(path, "b")
    other = b.deSerializeFMUstate(blob)
    b.setFMUState(other)
    other_instance = run(b, 50, 50)
    failures = 0
    for label, series in [("set state", again), ("deserialised", from_bytes),
                          ("deserialised into another instance", other_instance)]:
        if series != reference:
            worst = max(abs(x - y) for r, s in zip(reference, series) for x, y in zip(r, s))
            print(f"{path}: {label}: differs from the first run by up to {worst:e}")
            failures += 1
        else:
            print(f"{path}: {label}: bit-identical over {len(series)} steps")
    print(f"serialised state: {len(blob)} bytes")
    for slave in (a, b):
        slave.terminate()
        slave.freeInstance()
    return failures


def derivatives(path, rows):
    """After 20 steps, the step derivative (slender's extension) of the named
    outputs for a seed of each input, against central differences of the same step from the
    saved state; returns the number of mismatches."""
    md, a = instance(path, "a")
    inputs = [v for v in md.modelVariables if v.causality == "input"]
    by_name = {v.name: v.valueReference for v in md.modelVariables}
    unknowns = [by_name[r] for r in rows.split(",")]
    in_refs = [v.valueReference for v in inputs]
    starts = [float(v.start) for v in inputs]
    h = 0.01

    def values(t):
        return [s + 0.05 * (1 + abs(s)) * math.sin(0.7 * t + i) for i, s in enumerate(starts)]

    for k in range(20):
        a.setReal(in_refs, values(k * h))
        a.doStep(k * h, h)
    saved = a.getFMUState()
    t = 20 * h
    u = values(t)

    def step(u_step):
        a.setFMUState(saved)
        a.setReal(in_refs, u_step)
        a.doStep(t, h)
        return a.getReal(unknowns)

    step(u)
    # The step Jacobian through slender's extension (FMI 2.0's signature).
    ext = a.dll.slenderGetStepDerivative
    ext.argtypes = [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint), ctypes.c_size_t,
                    ctypes.POINTER(ctypes.c_uint), ctypes.c_size_t,
                    ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double)]
    ext.restype = ctypes.c_int
    columns = []
    for j in range(len(u)):
        seed = [1.0 if i == j else 0.0 for i in range(len(u))]
        out = (ctypes.c_double * len(unknowns))()
        status = ext(a.component, (ctypes.c_uint * len(unknowns))(*unknowns), len(unknowns),
                     (ctypes.c_uint * len(in_refs))(*in_refs), len(in_refs),
                     (ctypes.c_double * len(seed))(*seed), out)
        if status != 0:
            print(f"{path}: slenderGetStepDerivative returned status {status}")
            return 1
        columns.append(list(out))
    # The standard's directional derivative is the derivative at an instant:
    # zero for a unit whose outputs depend on its state only (declared by
    # providesDirectionalDerivative), refused for one with feedthrough.
    provides = md.coSimulation.providesDirectionalDerivative
    try:
        instant = a.getDirectionalDerivative(unknowns, in_refs, [1.0] * len(in_refs))
        answered = True
    except Exception:
        answered = False
    if answered != provides or (answered and any(v != 0.0 for v in instant)):
        print(f"{path}: the standard's derivative answered {answered} (declared {provides})"
              + (f": {list(instant)}" if answered else ""))
        return 1
    print(f"{path}: the standard's directional derivative at an instant "
          + ("is zero" if provides else "is refused (feedthrough)"))
    failures = 0
    worst = 0.0
    for j in range(len(u)):
        fd = []
        for delta in (1e-6 * max(abs(u[j]), 1.0), 1e-4 * max(abs(u[j]), 1.0)):
            up = list(u)
            up[j] += delta
            down = list(u)
            down[j] -= delta
            yu, yd = step(up), step(down)
            fd.append([(p - m) / (2 * delta) for p, m in zip(yu, yd)])
        for i, name in enumerate(rows.split(",")):
            scale = max(1e-300, max(abs(columns[k][i]) for k in range(len(u))))
            diff = min(abs(columns[j][i] - fd[0][i]), abs(columns[j][i] - fd[1][i])) / scale
            worst = max(worst, diff)
            if diff > 1e-3:
                print(f"{path}: d {name} / d input {j}: {columns[j][i]:e}, differences {fd[0][i]:e} / {fd[1][i]:e}")
                failures += 1
    print(f"{path}: directional derivatives of {len(unknowns)} outputs by {len(u)} inputs, "
          f"largest difference to central differences {worst:.2e} of the row")
    a.freeFMUState(saved)
    a.terminate()
    a.freeInstance()
    return failures


def arrays(path, stop, step):
    """Simulates a section's FMI 3.0 FMU in FMPy and checks at every output
    point, bit for bit, that a nonlinear section's node arrays end at its end
    positions and its largest element tension is its max_tension output, or
    that a cable's first and last element tensions are its end tensions."""
    result = simulate_fmu(path, stop_time=float(stop), output_interval=float(step))
    cable = "top_tension" in result.dtype.names
    failures = 0
    for row in result:
        x, z, tension = row["x"], row["z"], row["tension"]
        if cable:
            # Bottom first; the end tensions are the first and last elements'.
            checks = [(tension[0], row["bottom_tension"]), (tension[-1], row["top_tension"])]
        else:
            checks = [
                (x[0], row["start_position_x"]), (x[-1], row["end_position_x"]),
                (z[0], row["start_position_z"]), (z[-1], row["end_position_z"]),
                (max(tension), row["max_tension"]),
            ]
        failures += sum(1 for a, b in checks if a != b)
    print(f"{path}: {len(result)} output points, {len(result[0]['x'])} nodes, "
          f"{len(result[0]['tension'])} elements, {failures} disagreements")
    return failures


def end_checks(row, names):
    """A row's array ends against its scalar outputs, bit for bit: a cable's
    end tensions, a 3D line's end positions (the names present decide)."""
    if "bottom_tension" in names:
        return [(row["tension"][0], row["bottom_tension"]), (row["tension"][-1], row["top_tension"])]
    return [(row["x"][0], row["start_position_x"]), (row["x"][-1], row["end_position_x"]),
            (row["z"][-1], row["end_position_z"])]


def resize(path, parameter, value):
    """Changes an FMI 3.0 section's mesh through `parameter` and reads its
    arrays as an importer that follows FMI 3.0's structural parameters would:
    (1) the sizes read after initialisation, (2) set in Configuration Mode
    before it (and a wrong one refused), (3) FMPy's simulate_fmu, whose array shapes come from the
    description's starts, given a description with the sizes read in (1)."""
    md = read_model_description(path)
    folder = extract(path)
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    exported = {v.name: int(v.start) for v in md.modelVariables if v.name in ("n_nodes", "n_elements")}

    def slave(sizes):
        s = FMU3Slave(guid=md.guid, unzipDirectory=folder,
                      modelIdentifier=md.coSimulation.modelIdentifier, instanceName="resized")
        s.instantiate()
        s.setInt32([vrs[parameter]], [int(value)])
        if sizes:
            # FMI 3.0: structural parameters are set in Configuration Mode.
            s.enterConfigurationMode()
            s.setUInt64([vrs["n_nodes"], vrs["n_elements"]], list(sizes))
            s.exitConfigurationMode()
        s.enterInitializationMode(startTime=0.0)
        s.exitInitializationMode()
        return s

    failures = 0
    s = slave(None)
    nodes, elements = s.getUInt64([vrs["n_nodes"], vrs["n_elements"]])
    s.doStep(0.0, 0.01)
    x = s.getFloat64([vrs["x"]], nValues=nodes)
    tension = s.getFloat64([vrs["tension"]], nValues=elements)
    s.terminate()
    s.freeInstance()
    print(f"{path}: {parameter} = {value}: {nodes} nodes, {elements} elements "
          f"(exported {exported['n_nodes']}, {exported['n_elements']}), "
          f"{len(x)} x and {len(tension)} tension values")
    failures += (nodes != elements + 1) + (nodes == exported["n_nodes"])
    failures += (len(x) != nodes) + (not all(math.isfinite(v) for v in x + tension))
    s = slave((nodes, elements))
    s.terminate()
    s.freeInstance()
    try:
        slave((exported["n_nodes"], exported["n_elements"]))
        print("a wrong n_nodes was taken")
        failures += 1
    except Exception as e:
        print(f"a wrong n_nodes refused: {e}")
    sized = read_model_description(path)
    for v in sized.modelVariables:
        if v.name in ("n_nodes", "n_elements"):
            v.start = str(nodes if v.name == "n_nodes" else elements)
    for v in sized.modelVariables:
        if v.dimensions:
            v.shape = tuple(int(d.variable.start) for d in v.dimensions)
    result = simulate_fmu(path, model_description=sized, stop_time=0.5, output_interval=0.01,
                          start_values={parameter: int(value)})
    names = result.dtype.names
    disagreements = sum(1 for row in result for a, b in end_checks(row, names) if a != b)
    print(f"simulate_fmu: {len(result)} rows of {len(result[0]['x'])} nodes, "
          f"{disagreements} disagreements")
    failures += disagreements + (len(result[0]["x"]) != nodes)
    print(f"{failures} failures")
    return failures


if __name__ == "__main__":
    command, args = sys.argv[1], sys.argv[2:]
    if command == "validate":
        sys.exit(validate(args))
    if command == "simulate":
        sys.exit(simulate(args[0], args[1], args[2], args[3], args[4:]))
    if command == "state":
        sys.exit(state(args[0]))
    if command == "arrays":
        sys.exit(arrays(args[0], args[1], args[2]))
    if command == "resize":
        sys.exit(resize(args[0], args[1], args[2]))
    if command == "derivatives":
        sys.exit(derivatives(args[0], args[1]))
    sys.exit(f"unknown command {command}")
