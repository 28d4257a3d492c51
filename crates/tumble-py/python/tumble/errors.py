"""Exceptions raised by Tumble.

Every error the engine reports is a :class:`TumbleError`; the message is the core's own
("body \"box\": density must be finite and > 0, got -1"). Bad values are also a
:class:`ValueError`, and handles that no longer name anything are also a :class:`LookupError`,
so code that catches the built-in exceptions keeps working.
"""


class TumbleError(Exception):
    """Base class of every error raised by Tumble."""


class TumbleValueError(TumbleError, ValueError):
    """A value was rejected: non-finite numbers, negative density, a wrongly shaped array, ..."""


class StaleHandleError(TumbleError, LookupError):
    """A body or joint handle that no longer names anything in this world (removed, or from
    another world)."""


__all__ = ["TumbleError", "TumbleValueError", "StaleHandleError"]
