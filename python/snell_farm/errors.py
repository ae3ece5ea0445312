"""The errors the driver expects: printed as one message, never as a traceback."""


class FarmError(Exception):
    """A job that cannot go on, with the message to print and the exit status to leave with.

    Exit status 2 is a bad command line or scene (as snell's own), 1 a failure while
    rendering or writing.
    """

    def __init__(self, message: str, exit_code: int = 1) -> None:
        super().__init__(message)
        self.message = message
        self.exit_code = exit_code

    def __str__(self) -> str:
        return self.message
