"""What two results.json of the same config and data may differ in, removed for comparison."""
import re

NOTE_TIME = re.compile(r", [0-9]+\.[0-9]{3} s($|[;,)])")


def drop_times(value):
    """results.json without what differs between two runs of the same data: the wall times
    ("time_seconds", "seconds", a note's ", 4.969 s") and the config's name."""
    if isinstance(value, str):
        return NOTE_TIME.sub(r", <time> s\1", value)
    if isinstance(value, dict):
        return {k: drop_times(v) for k, v in value.items()
                if k not in ("time_seconds", "seconds", "config")}
    if isinstance(value, list):
        return [drop_times(v) for v in value]
    return value



def same_to_digits(a, b, digits=9):
    """Two results.json trees equal but for numbers that agree to `digits` significant digits
    (absolutely, below 1): one thread and two round the solver's sums in another order, which
    moves the last bits of every estimate (up to 7e-11 on the tanker's run)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(same_to_digits(a[k], b[k], digits) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same_to_digits(x, y, digits) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float):
        return a == b or abs(a - b) <= 10.0**-digits * max(1.0, abs(a), abs(b))
    return a == b
