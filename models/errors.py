"""The one kind of error a user can fix by changing their input (an instruction, a room type, a solver's name, a
room list): the CLI shows it as one line with exit status 2, the API as a 422, a batch as the line's message alone.
Any other exception is a fault of ours and is reported with where it happened."""


class InputError(ValueError):
    """Input the user can fix; the message names the problem in one line."""
