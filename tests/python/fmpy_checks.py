"""FMPy-side checks of slender's exported FMUs, run by tests/tests/fmi_python.rs.

    fmpy_checks.py validate FMU...            problems per FMU; exit code = their number
    fmpy_checks.py simulate FMU CSV STOP STEP [NAME=VALUE...]
    fmpy_checks.py state FMU                  FMU state save/restore/serialise round trips
"""

import math
import sys

from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi2 import FMU2Slave
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


def instance(path, name):
    md = read_model_description(path)
    folder = extract(path)
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


if __name__ == "__main__":
    command, args = sys.argv[1], sys.argv[2:]
    if command == "validate":
        sys.exit(validate(args))
    if command == "simulate":
        sys.exit(simulate(args[0], args[1], args[2], args[3], args[4:]))
    if command == "state":
        sys.exit(state(args[0]))
    sys.exit(f"unknown command {command}")
