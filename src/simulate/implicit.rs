//! Implicit Runge–Kutta methods: Radau IIA (order 5) and Gauss–Legendre (order 6).
