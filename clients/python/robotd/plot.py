"""Render a robotd recording's joint trajectories to an image: one subplot per joint, measured
positions (/joint_states) as a line, commanded positions (/control_command) as steps, the
joint's position limits at record time written in a corner and drawn as dashed lines when they
are near the data (a far one would flatten the curves).

    python3 -m robotd.plot run.rdrec -o run.png [--device arm]

Needs matplotlib (Debian: python3-matplotlib, for /usr/bin/python3); draws without a display."""
import argparse
import sys

from . import recording

INCHES_PER_JOINT = 1.8
FIGURE_WIDTH_INCHES = 10


def _load_pyplot():
    try:
        import matplotlib
    except ImportError:
        raise SystemExit(f"robotd.plot: matplotlib is missing for {sys.executable}; install it (Debian: sudo apt-get "
                         "install python3-matplotlib) and run with that python3, e.g. /usr/bin/python3") from None
    matplotlib.use("Agg")  # files only: no display needed
    import matplotlib.pyplot as pyplot
    return pyplot


def joint_series(run, device):
    """({joint: ([t_s], [position])} measured, the same commanded) for `device` of `run`."""
    measured, commanded = {}, {}
    for state in run.joint_states:
        if state.device == device.name:
            for joint, position in enumerate(state.position):
                times, values = measured.setdefault(joint, ([], []))
                times.append(state.time_ns * 1e-9)
                values.append(position)
    for command in run.commands:
        if command.device == device.name and len(command.positions) == len(command.motor_ids):
            for motor, position in zip(command.motor_ids, command.positions):
                times, values = commanded.setdefault(motor, ([], []))
                times.append(command.time_ns * 1e-9)
                values.append(position)
    return measured, commanded


def view(low, high, limits):
    """The y range for data from `low` to `high`: padded, and stretched to a limit only when it is
    near, since a far one would flatten the curves (the limits are also written on the plot)."""
    pad = max(0.15 * (high - low), 0.05)
    low, high = low - pad, high + pad
    near = high - low
    for limit in limits:
        if low - near <= limit < low:
            low = limit - 0.1 * pad
        elif high < limit <= high + near:
            high = limit + 0.1 * pad
    return low, high


def plot(run, devices, output):
    """Draws `devices` of `run` into the image file `output`; returns how many joints it drew."""
    pyplot = _load_pyplot()
    rows = [(device, joint) for device in devices for joint in range(len(device.joint_names))]
    figure, axes = pyplot.subplots(len(rows), 1, sharex=True, squeeze=False,
                                   figsize=(FIGURE_WIDTH_INCHES, max(3.0, INCHES_PER_JOINT * len(rows))))
    series = {device.name: joint_series(run, device) for device in devices}
    for (device, joint), (axis,) in zip(rows, axes):
        measured, commanded = series[device.name]
        if joint in measured:
            axis.plot(*measured[joint], color="tab:blue", linewidth=1.2, label="measured")
        if joint in commanded:
            axis.step(*commanded[joint], where="post", color="tab:orange", linewidth=1.0, label="commanded")
        limits = [values[joint] for values in (device.position_min, device.position_max) if joint < len(values)]
        for limit in limits:
            axis.axhline(limit, color="tab:red", linestyle="--", linewidth=0.8)
        values = [*measured.get(joint, ((), ()))[1], *commanded.get(joint, ((), ()))[1]]
        if values:
            axis.set_ylim(*view(min(values), max(values), limits))
        if len(limits) == 2:
            axis.text(0.01, 0.95, f"limits {limits[0]:.2f} .. {limits[1]:.2f} rad", transform=axis.transAxes,
                      verticalalignment="top", fontsize="small", color="tab:red")
        axis.set_ylabel(f"{device.name}\n{device.joint_names[joint]}\nrad")
        axis.grid(True, alpha=0.3)
    axes[0][0].legend(loc="upper right", fontsize="small")
    axes[-1][0].set_xlabel("time since the recording began, s")
    start = run.description.get("start_time", "")
    figure.suptitle(f"{run.path} ({start}); dashed: position limits at record time, where near the data")
    figure.tight_layout()
    figure.savefig(output)
    pyplot.close(figure)
    return len(rows)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m robotd.plot", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("recording", help="a file written by robotctl record")
    parser.add_argument("-o", "--output", required=True, help="the image to write (PNG; .svg and .pdf work too)")
    parser.add_argument("--device", help="only this device (default: every device recorded)")
    args = parser.parse_args(argv)
    try:
        run = recording.read(args.recording)
        devices = [run.device(args.device)] if args.device else list(run.devices)
    except (OSError, recording.RecordingError) as error:
        print(f"robotd.plot: {error}", file=sys.stderr)
        return 1
    except KeyError as error:
        print(f"robotd.plot: {error.args[0]}", file=sys.stderr)
        return 1
    for problem in run.problems:
        print(f"robotd.plot: note: {problem}", file=sys.stderr)
    devices = [device for device in devices if device.joint_names]
    if not devices or not (run.joint_states or run.commands):
        print(f"robotd.plot: {args.recording} has no joint states or commands to plot; expected a recording with "
              "joint_states or control_command", file=sys.stderr)
        return 1
    joints = plot(run, devices, args.output)
    print(f"wrote {args.output}: {joints} joints of {', '.join(repr(d.name) for d in devices)} over "
          f"{run.duration_ns * 1e-9:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
