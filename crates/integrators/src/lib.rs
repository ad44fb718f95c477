//! Solvers for friction problems (issue 3): RK4, Dormand–Prince 5(4), implicit Euler with Newton, event location and stick–slip switching, and diffsol behind the same interface.
