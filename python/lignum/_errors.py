"""Exceptions and warnings of the Python package."""


class LignumError(RuntimeError):
    """A Lignum call failed.

    Attributes
    ----------
    flag : int
        Lignum's return flag (negative), e.g. ``-22``.
    name : str
        Its name, e.g. ``"LGN_ILL_INPUT"`` (``LGNGetReturnFlagName``).
    function : str
        The C function that reported it (``"LGNSetGenAlpha"``), or ``""``.
    message : str
        Lignum's message, naming the argument or the failed callback.
    """

    def __init__(self, flag, name, function="", message=""):
        self.flag = int(flag)
        self.name = name
        self.function = function
        self.message = message
        text = f"{name} ({flag})"
        if function:
            text += f" in {function}"
        if message:
            text += f": {message}"
        super().__init__(text)


class LignumWarning(UserWarning):
    """A warning of Lignum (e.g. redundant constraints left out)."""
