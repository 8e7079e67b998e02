"""The codes the kernels switch on: integrators, contact models and kinds of contact, one enum each.

Each member's ``label`` (its name in lower case) is the name a scene file uses:
``simulation.integrator = "imex_euler"``, ``[contact.ball_net]``. Numba kernels take the
members as plain integers.
"""

from __future__ import annotations

from enum import IntEnum

from netgym.errors import InvalidArgumentError


class _Labelled(IntEnum):
    @property
    def label(self) -> str:
        """The member's name in scene files."""
        return self.name.lower()

    @classmethod
    def labels(cls) -> tuple[str, ...]:
        """Every member's label, in code order."""
        return tuple(member.label for member in cls)

    @classmethod
    def parse(cls, label: str) -> "_Labelled":
        """The member named ``label``; a ValueError listing the choices otherwise."""
        for member in cls:
            if member.label == label:
                return member
        raise InvalidArgumentError(f"{cls.__name__.lower()} = {label!r} is not one of {list(cls.labels())}")


class Integrator(_Labelled):
    """Time integrators of the smooth forces (see :mod:`netgym.physics.kernels.integrators`)."""

    EXPLICIT_EULER = 0
    SYMPLECTIC_EULER = 1
    RK4 = 2
    IMPLICIT_EULER = 3
    IMEX_EULER = 4


class ContactModel(_Labelled):
    """How contacts act: ``impulse``, projections and impulses after each substep (the
    default, :mod:`netgym.physics.kernels.impulse_contacts`), or ``compliant``, Hunt-Crossley forces inside
    the integrator (:mod:`netgym.physics.compliant`)."""

    IMPULSE = 0
    COMPLIANT = 1


class Contact(_Labelled):
    """Kinds of contact, each with its own (restitution, friction): rows of the contact table."""

    BALL_NET = 0
    BALL_POLE = 1
    BALL_BALL = 2
    BALL_GROUND = 3
    NET_GROUND = 4


class SpringKind(_Labelled):
    """Kinds of spring, each with its own (ks, kd): structural (grid neighbours), shear
    (diagonals), bending (second neighbours)."""

    STRUCTURAL = 0
    SHEAR = 1
    BENDING = 2
