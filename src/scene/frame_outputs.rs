//! A frame's own outputs: a support at an angle's reactions in its own frame (`_R1`, `_R2`),
//! truss bar forces (`<member>_N_start`, `_N_end`) and link forces (`<link>_force`).
use super::variable_kinds::{
    output, OutputId, Variable, BAR_FORCE_VR, LINK_FORCE_VR, SUPPORT_FRAME_VR,
};
use super::Scene;

/// A frame's own outputs: supports at an angle in their frame (`_R1`, `_R2`), truss bar forces
/// (`<member>_N_start`, `_N_end`) and link forces (`<link>_force`).
pub(super) fn frame_outputs(scene: &Scene) -> Vec<Variable> {
    let mut vars = Vec::new();
    for (k, s) in scene
        .supports
        .iter()
        .enumerate()
        .filter(|(_, s)| s.angle != 0.0)
    {
        for c in 0..2 {
            vars.push(output(
                format!("{}_R{}", s.name, c + 1),
                SUPPORT_FRAME_VR + 2 * k as u32 + c as u32,
                Some("N"),
                format!(
                    "Reaction force of support {} on the structure along its own axis {} (turned \
                     by {} degrees from e{}); averaged like {0}_Rx",
                    s.name,
                    c + 1,
                    s.angle,
                    c + 1
                ),
                OutputId::SupportFrame {
                    support: k,
                    component: c,
                },
            ));
        }
    }
    let Some(frame) = &scene.frame else {
        return vars;
    };
    for (m, member) in frame.members.iter().enumerate() {
        if member.kind != super::frame::MemberKind::Truss {
            continue;
        }
        for (end, suffix) in ["start", "end"].iter().enumerate() {
            vars.push(output(
                format!("{}_N_{suffix}", member.name),
                BAR_FORCE_VR + 2 * m as u32 + end as u32,
                Some("N"),
                format!(
                    "Normal force of {} {} at its {suffix} (tension positive{})",
                    if member.cable {
                        "cable"
                    } else {
                        "truss member"
                    },
                    member.name,
                    if member.cable { "; 0 while slack" } else { "" }
                ),
                OutputId::BarForce { member: m, end },
            ));
        }
    }
    for (k, l) in frame.links.iter().enumerate() {
        vars.push(output(
            format!("{}_force", l.name),
            LINK_FORCE_VR + k as u32,
            Some("N"),
            format!(
                "Force of link {} along its current line (tension positive), spring and dashpot; \
                 averaged over the last communication step (before the first step: the static \
                 force)",
                l.name
            ),
            OutputId::LinkForce(k),
        ));
    }
    vars
}
