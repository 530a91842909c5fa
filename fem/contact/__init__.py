"""Penalty contact between slave and master surfaces, solved on the Schur complement of the gaps.

One idea per module, in the order of a solve (``fem.analysis``):

- :mod:`fem.contact.faces`: bilinear faces: shape functions, closest-point projection, surface mass;
- :mod:`fem.contact.search`: the constraints of the contact pairs: slave points projected on the
  master, their gaps, gap gradients, areas and penalties, the candidates and the seed of the
  active set (:func:`contact_set`), and the nodal pressure of contact forces (``ContactSet.pressure``);
- :mod:`fem.contact.active_set`: the penalty contact problem reduced to the candidate gaps and the
  free rigid DOFs, and its primal-dual active-set solution (:func:`penalty_active_set`);
- :mod:`fem.contact.patch`: the Hertz-equivalent contact patch of nodal forces (:func:`contact_patch`).
"""

from fem.contact.active_set import ActiveSetSolution, ReducedContact, active_set, penalty_active_set
from fem.contact.faces import bilinear, project_to_faces, surface_mass
from fem.contact.patch import ContactPatch, contact_patch
from fem.contact.search import ContactSet, contact_set

__all__ = ["ContactSet", "contact_set", "ReducedContact", "ActiveSetSolution", "active_set", "penalty_active_set",
           "bilinear", "project_to_faces", "surface_mass", "ContactPatch", "contact_patch"]
