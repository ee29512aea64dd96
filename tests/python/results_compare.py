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
