"""Linear elasticity, penalty contact, rigid bodies and loads, stress recovery."""

__all__: list[str] = []
