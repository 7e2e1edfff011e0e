//! Static Newton and the implicit midpoint rule.
