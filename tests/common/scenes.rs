//! Scenes more than one test builds on.

/// Lee's frame (L = 120, EI = 1440, the load `P` at 24 from the corner, pinned at both ends),
/// 40 elements per member: the classic snap-back benchmark of frame codes.
pub const LEE_FRAME: &str = r#"
name = "Lee"
[defaults]
E = 720.0
nu = 0.3
rho = 1e-6
elements = 40
[section]
b = 3.0
h = 2.0
[[joint]]
name = "base"
x = 0.0
y = 0.0
[[joint]]
name = "corner"
x = 0.0
y = 120.0
[[joint]]
name = "end"
x = 120.0
y = 120.0
[[member]]
name = "column"
from = "base"
to = "corner"
[[member]]
name = "beam"
from = "corner"
to = "end"
[[support]]
name = "pin_base"
joint = "base"
fix = ["u1", "u2"]
[[support]]
name = "pin_end"
joint = "end"
fix = ["u1", "u2"]
[[load]]
name = "P"
kind = "point"
member = "beam"
at = 0.2
direction = "-e2"
value = 0.0
"#;
