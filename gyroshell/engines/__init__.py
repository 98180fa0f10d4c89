"""The solvers of the tape's semi-discrete system M a + G v + K w = F: static deflection,
divergence, Newmark time marching, the eigen-solvers, critical speeds, frequency response.
"""
