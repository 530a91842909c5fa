"""Contact of two placed flanks, shared by every analysis: tangency, edge and corner systems, foot points and
the instantaneous contact ellipse.
"""

from tca.contact.systems import PlacedFlank, corner_system, edge_edge_system, edge_system, foot_points, tangency_system
from tca.contact.ellipse import contact_ellipse

__all__ = ["PlacedFlank", "corner_system", "edge_edge_system", "edge_system", "foot_points", "tangency_system", "contact_ellipse"]
