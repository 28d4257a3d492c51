//! `--what`: which panels to draw, parsed and checked against what the source can give.

use super::series::{vector_lines, Line, Panel, PlotData};

pub const WHAT_HELP: &str = "energy, momentum, angular_momentum, omega[:BODY], omega_body[:BODY]";

/// One requested panel.
#[derive(Clone, Debug, PartialEq)]
pub enum What {
    Energy,
    Momentum,
    AngularMomentum,
    /// ω of a body in the world frame (None: the only body).
    Omega(Option<String>),
    /// ω of a body in its own frame.
    OmegaBody(Option<String>),
}

/// Parses a comma-separated list such as `energy,omega:handle`.
pub fn parse_what(text: &str) -> Result<Vec<What>, String> {
    let mut list = Vec::new();
    for item in text.split(',').map(str::trim) {
        let what = match item.split_once(':') {
            Some(("omega", body)) if !body.is_empty() => What::Omega(Some(body.to_string())),
            Some(("omega_body", body)) if !body.is_empty() => What::OmegaBody(Some(body.to_string())),
            None if item == "omega" => What::Omega(None),
            None if item == "omega_body" => What::OmegaBody(None),
            None if item == "energy" => What::Energy,
            None if item == "momentum" => What::Momentum,
            None if item == "angular_momentum" || item == "L" => What::AngularMomentum,
            _ => {
                return Err(format!(
                    "unknown --what `{item}`: expected a comma-separated list of {WHAT_HELP}"
                ))
            }
        };
        list.push(what);
    }
    Ok(list)
}

const NEEDS_SCENE: &str =
    "needs the bodies' masses, which a recording does not hold: pass --scene SCENE.toml";

/// The panels for `what`, or why one cannot be drawn from `data`.
pub fn panels(data: &PlotData, what: &[What]) -> Result<Vec<Panel>, String> {
    what.iter()
        .map(|w| match w {
            What::Energy => {
                let (kinetic, potential) = data.energy.as_ref().ok_or(format!("energy {NEEDS_SCENE}"))?;
                let total = kinetic.iter().zip(potential).map(|(k, p)| k + p).collect();
                Ok(Panel {
                    title: "Energy (dynamic bodies; potential zero at z = 0)".into(),
                    y_label: "energy (J)".into(),
                    lines: vec![
                        Line { label: "kinetic".into(), values: kinetic.clone() },
                        Line { label: "potential".into(), values: potential.clone() },
                        Line { label: "total".into(), values: total },
                    ],
                })
            }
            What::Momentum => {
                let p = data.momentum.as_ref().ok_or(format!("momentum {NEEDS_SCENE}"))?;
                Ok(Panel {
                    title: "Linear momentum".into(),
                    y_label: "p (kg m/s)".into(),
                    lines: vector_lines("p", p),
                })
            }
            What::AngularMomentum => {
                let l = data.angular_momentum.as_ref().ok_or(format!("angular_momentum {NEEDS_SCENE}"))?;
                Ok(Panel {
                    title: "Angular momentum about the centre of mass (world frame)".into(),
                    y_label: "L (kg m²/s)".into(),
                    lines: vector_lines("L", l),
                })
            }
            What::Omega(body) | What::OmegaBody(body) => {
                let body_frame = matches!(w, What::OmegaBody(_));
                let key = if body_frame { "omega_body" } else { "omega" };
                let names = || data.omega.iter().map(|b| b.name.as_str()).collect::<Vec<_>>().join(", ");
                let track = match body {
                    Some(name) => data.omega.iter().find(|b| &b.name == name).ok_or_else(|| {
                        format!("{key}:{name}: no body called \"{name}\" (bodies: {})", names())
                    })?,
                    None if data.omega.len() == 1 => &data.omega[0],
                    None => {
                        return Err(format!(
                            "{key}: there are several bodies; name one, as {key}:BODY ({})",
                            names()
                        ))
                    }
                };
                let (frame, values) = if body_frame {
                    ("body", track.omega_body())
                } else {
                    ("world", track.omega_world.clone())
                };
                Ok(Panel {
                    title: format!("Angular velocity of {} ({frame} frame)", track.name),
                    y_label: "ω (rad/s)".into(),
                    lines: vector_lines("ω", &values),
                })
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_lists_and_rejects_unknown_items() {
        assert_eq!(
            parse_what("energy, omega:handle,momentum,omega,omega_body:a").unwrap(),
            vec![
                What::Energy,
                What::Omega(Some("handle".into())),
                What::Momentum,
                What::Omega(None),
                What::OmegaBody(Some("a".into()))
            ]
        );
        let err = parse_what("energy,spin").unwrap_err();
        assert!(err.contains("unknown --what `spin`"), "{err}");
        assert!(parse_what("omega:").is_err());
    }
}
