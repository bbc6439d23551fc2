"""Runs an SSP in libcosim (libcosimpy) with the fixed step of its OSP
annotation and prints chosen Real variables after every step as CSV (step
number, then one column per variable), for tests/tests/ssp.rs to compare with
slender's runs of the same system.

Usage: ssp_libcosim.py SYSTEM.ssp STEPS UNIT.VARIABLE [UNIT.VARIABLE ...]
"""

import sys

from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver


def reference(execution, signal):
    """(slave index, value reference) of `unit.variable`."""
    unit, variable = signal.split(".", 1)
    index = execution.slave_index_from_instance_name(unit)
    for v in execution.slave_variables(index):
        if v.name.decode() == variable:
            return index, v.reference
    raise SystemExit(f"{signal}: no such variable")


def main():
    path, steps, signals = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
    log_output_level(CosimLogLevel.ERROR)
    execution = CosimExecution.from_ssp_file(path)
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer)
    refs = [reference(execution, s) for s in signals]
    print("step," + ",".join(signals))
    for k in range(1, steps + 1):
        if not execution.step():
            raise SystemExit(f"libcosim failed at step {k}")
        values = [observer.last_real_values(i, [r])[0] for i, r in refs]
        print(f"{k}," + ",".join(repr(v) for v in values))


if __name__ == "__main__":
    main()
