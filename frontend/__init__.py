"""The browser studio, built on viser: instruction -> task graph -> animated placement -> stored scene."""
