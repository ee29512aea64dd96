"""The errors the package raises, with the messages the CLI prints."""


class VesselidError(Exception):
    """Any error vesselid reports."""


class ConfigError(VesselidError):
    """The config is wrong: the message names the file (or "config"), line and key."""


class DataError(VesselidError):
    """A record is wrong or missing: the message names the experiment, row or file line."""


class RunError(VesselidError):
    """The run could not finish (a stage failed, the output folder cannot be written)."""
