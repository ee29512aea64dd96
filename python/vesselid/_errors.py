"""The errors the package raises, with the messages the CLI prints."""


class VesselidError(Exception):
    """Any error vesselid reports."""


class ConfigError(VesselidError):
    """The config is wrong: the message names the file (or "config"), line and key."""


class DataError(VesselidError):
    """A record is wrong or missing: the message names the experiment, row or file line."""


class RunError(VesselidError):
    """The run could not finish (a stage failed, the output folder cannot be written)."""


def raise_for(kind, message):
    if kind == "config":
        raise ConfigError(message)
    if kind == "data":
        raise DataError(message)
    if kind == "interrupted":
        raise KeyboardInterrupt(message)
    raise RunError(message)
