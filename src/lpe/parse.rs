//! Reading a light path expression (OSL's syntax) into a tree: events (`C`, `L`, `<RD>`,
//! `'label'`), sets (`[DG]`, `[^D]`), groups, alternatives and repetition. Every node keeps
//! the column it starts at, so that a later check (a name the scene lacks) can point at it.

use super::LpeError;

/// What kind of event an event pattern asks for: its type (the first letter inside `<>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventType {
    /// Any event (`.`).
    Any,
    /// The camera (`C`).
    Camera,
    /// A reflection (`R`).
    Reflect,
    /// A transmission (`T`).
    Transmit,
    /// Any light: a light, a glowing surface or the sky (`L`).
    Light,
    /// A glowing surface (`O`).
    Object,
    /// The environment or the background (`B`).
    Background,
}

/// How an event scattered (the second letter inside `<>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scattering {
    /// Any way (`.`).
    Any,
    /// Diffuse (`D`).
    Diffuse,
    /// Glossy: rough microfacets, Phong's highlight (`G`).
    Glossy,
    /// Singular: a mirror or smooth glass (`S`).
    Singular,
}

/// One event pattern: a type, a scattering and perhaps a label (a material's name for a
/// scattering event, a light's or a glowing object's name for a light).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EventPattern {
    /// The type asked for.
    pub kind: EventType,
    /// The scattering asked for.
    pub scattering: Scattering,
    /// The label, and the column it starts at.
    pub label: Option<(String, usize)>,
    /// Where the pattern starts (1-based column).
    pub column: usize,
}

/// A parsed expression.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Node {
    /// One event matching the pattern.
    Event(EventPattern),
    /// One event matching any of the patterns (`[...]`), or, negated, none of them
    /// (`[^...]`).
    Set {
        /// The patterns.
        items: Vec<EventPattern>,
        /// Whether the set is negated.
        negated: bool,
    },
    /// Each part in turn.
    Seq(Vec<Node>),
    /// Any one of the parts.
    Alt(Vec<Node>),
    /// The part `min` to `max` times (`None`: any number more).
    Repeat {
        /// The part repeated.
        node: Box<Node>,
        /// Fewest times.
        min: u32,
        /// Most times, if bounded.
        max: Option<u32>,
    },
}

/// The most a counted repetition (`{n,m}`) may give, so that the automaton stays small.
pub const MAX_COUNT: u32 = 16;

/// Reads `text` as an expression.
pub fn parse(text: &str) -> Result<Node, LpeError> {
    let chars: Vec<char> = text.chars().collect();
    let mut p = Parser { chars, at: 0 };
    p.skip_spaces();
    if p.at == p.chars.len() {
        return Err(LpeError::new(
            1,
            "the expression is empty",
            "write the paths to keep, such as `C<RD>L` (light from a light, reflected once by a diffuse surface)",
        ));
    }
    let node = p.alternatives()?;
    if let Some(c) = p.peek() {
        return Err(if c == ')' {
            LpeError::new(
                p.column(),
                "this `)` closes no `(`",
                "remove it, or open the group with `(`",
            )
        } else {
            LpeError::new(
                p.column(),
                format!("unexpected `{c}`"),
                "an event, a set `[...]`, a group `(...)` or an operator `* + ? | {n,m}` was expected",
            )
        });
    }
    Ok(node)
}

struct Parser {
    chars: Vec<char>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn column(&self) -> usize {
        self.at + 1
    }

    fn skip_spaces(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.at += 1;
        }
    }

    fn alternatives(&mut self) -> Result<Node, LpeError> {
        let mut alts = vec![self.sequence()?];
        while self.peek() == Some('|') {
            self.at += 1;
            self.skip_spaces();
            alts.push(self.sequence()?);
        }
        Ok(if alts.len() == 1 {
            alts.pop().expect("one alternative")
        } else {
            Node::Alt(alts)
        })
    }

    fn sequence(&mut self) -> Result<Node, LpeError> {
        let mut parts = vec![];
        loop {
            self.skip_spaces();
            match self.peek() {
                None | Some('|') | Some(')') => break,
                _ => parts.push(self.repeated()?),
            }
        }
        if parts.is_empty() {
            let found = self
                .peek()
                .map_or("the end".to_string(), |c| format!("`{c}`"));
            return Err(LpeError::new(
                self.column(),
                format!("an event was expected before {found}"),
                "each side of `|` and each group needs at least one event, such as `C`, `D` or `L`",
            ));
        }
        Ok(if parts.len() == 1 {
            parts.pop().expect("one part")
        } else {
            Node::Seq(parts)
        })
    }

    fn repeated(&mut self) -> Result<Node, LpeError> {
        let mut node = self.atom()?;
        loop {
            let (min, max) = match self.peek() {
                Some('*') => (0, None),
                Some('+') => (1, None),
                Some('?') => (0, Some(1)),
                Some('{') => self.count()?,
                _ => return Ok(node),
            };
            // Past the operator (or the count's `}`).
            self.at += 1;
            node = Node::Repeat {
                node: Box::new(node),
                min,
                max,
            };
        }
    }

    /// `{n}`, `{n,}` or `{n,m}`, read up to (not past) its `}`.
    fn count(&mut self) -> Result<(u32, Option<u32>), LpeError> {
        let start = self.column();
        self.at += 1;
        let min = self.number(start)?;
        let max = if self.peek() == Some(',') {
            self.at += 1;
            if self.peek() == Some('}') {
                None
            } else {
                Some(self.number(start)?)
            }
        } else {
            Some(min)
        };
        if self.peek() != Some('}') {
            return Err(LpeError::new(
                self.column(),
                "a count `{n}`, `{n,}` or `{n,m}` is not closed",
                "close it with `}`",
            ));
        }
        if max.is_some_and(|m| m < min) {
            return Err(LpeError::new(
                start,
                "the count's most is below its fewest",
                "write `{fewest,most}`, such as `{1,3}`",
            ));
        }
        if max.unwrap_or(min) > MAX_COUNT {
            return Err(LpeError::new(
                start,
                format!("counts above {MAX_COUNT} are not taken"),
                "use `+` or `*` for any number",
            ));
        }
        Ok((min, max))
    }

    fn number(&mut self, start: usize) -> Result<u32, LpeError> {
        let from = self.at;
        while self.peek().is_some_and(|c| c.is_ascii_digit()) {
            self.at += 1;
        }
        let digits: String = self.chars[from..self.at].iter().collect();
        digits.parse().map_err(|_| {
            LpeError::new(
                if digits.is_empty() {
                    self.column()
                } else {
                    start
                },
                "a count needs a whole number",
                "write `{n}`, `{n,}` or `{n,m}`, such as `D{2}`",
            )
        })
    }

    fn atom(&mut self) -> Result<Node, LpeError> {
        let column = self.column();
        match self.peek() {
            Some('(') => {
                self.at += 1;
                self.skip_spaces();
                let inner = self.alternatives()?;
                if self.peek() != Some(')') {
                    return Err(LpeError::new(
                        column,
                        "this `(` is not closed",
                        "close the group with `)`",
                    ));
                }
                self.at += 1;
                Ok(inner)
            }
            Some('[') => self.set(),
            Some(c @ ('*' | '+' | '?' | '{')) => Err(LpeError::new(
                column,
                format!("`{c}` repeats the event before it, and there is none"),
                "put it after an event or a group, such as `D*`",
            )),
            _ => Ok(Node::Event(self.event()?)),
        }
    }

    fn set(&mut self) -> Result<Node, LpeError> {
        let column = self.column();
        self.at += 1;
        let negated = self.peek() == Some('^');
        if negated {
            self.at += 1;
        }
        let mut items = vec![];
        loop {
            self.skip_spaces();
            match self.peek() {
                Some(']') => {
                    self.at += 1;
                    break;
                }
                None => {
                    return Err(LpeError::new(
                        column,
                        "this `[` is not closed",
                        "close the set with `]`",
                    ));
                }
                _ => items.push(self.event()?),
            }
        }
        if items.is_empty() {
            return Err(LpeError::new(
                column,
                "the set is empty",
                "list the events it takes, such as `[DG]`",
            ));
        }
        Ok(Node::Set { items, negated })
    }

    /// One event: a letter or `.` (with a label after it, perhaps), `<type scattering
    /// 'label'>`, or a label alone.
    fn event(&mut self) -> Result<EventPattern, LpeError> {
        let column = self.column();
        let Some(c) = self.peek() else {
            return Err(LpeError::new(
                column,
                "an event was expected at the end",
                "end with the light, `L`",
            ));
        };
        if c == '<' {
            return self.bracketed();
        }
        if c == '\'' {
            let label = self.label()?;
            return Ok(EventPattern {
                kind: EventType::Any,
                scattering: Scattering::Any,
                label: Some(label),
                column,
            });
        }
        let (kind, scattering) = letter(c).ok_or_else(|| unknown_letter(c, column))?;
        self.at += 1;
        let label = if self.peek() == Some('\'') {
            Some(self.label()?)
        } else {
            None
        };
        Ok(EventPattern {
            kind,
            scattering,
            label,
            column,
        })
    }

    fn bracketed(&mut self) -> Result<EventPattern, LpeError> {
        let column = self.column();
        self.at += 1;
        self.skip_spaces();
        let kind_at = self.column();
        let kind = match self.peek() {
            Some('.') => EventType::Any,
            Some(c) => match letter(c) {
                Some((k, Scattering::Any)) if k != EventType::Any => k,
                Some(_) => {
                    return Err(LpeError::new(
                        kind_at,
                        format!("`{c}` is a scattering, and `<>` starts with the event's type"),
                        "write the type first: `<RD>` is a diffuse reflection, `<.D>` any diffuse event",
                    ));
                }
                None => return Err(unknown_letter(c, kind_at)),
            },
            None => return Err(unclosed_angle(column)),
        };
        self.at += 1;
        self.skip_spaces();
        let mut scattering = Scattering::Any;
        if let Some(c) = self.peek().filter(|&c| c != '>' && c != '\'') {
            let at = self.column();
            scattering = match letter(c) {
                Some((EventType::Any, s)) => s,
                Some(_) => {
                    return Err(LpeError::new(
                        at,
                        format!(
                            "`{c}` is an event type, and the second place in `<>` is the scattering"
                        ),
                        "use D (diffuse), G (glossy), S (singular) or `.` (any): `<RD>`",
                    ));
                }
                None => return Err(unknown_letter(c, at)),
            };
            self.at += 1;
            self.skip_spaces();
        }
        let label = if self.peek() == Some('\'') {
            Some(self.label()?)
        } else {
            None
        };
        self.skip_spaces();
        if self.peek() != Some('>') {
            return Err(match self.peek() {
                None => unclosed_angle(column),
                Some(c) => LpeError::new(
                    self.column(),
                    format!("unexpected `{c}` in `<>`"),
                    "`<>` holds a type, a scattering and a label: `<RD'floor'>`",
                ),
            });
        }
        self.at += 1;
        Ok(EventPattern {
            kind,
            scattering,
            label,
            column,
        })
    }

    /// A quoted label, `'name'`.
    fn label(&mut self) -> Result<(String, usize), LpeError> {
        let column = self.column();
        self.at += 1;
        let from = self.at;
        while self.peek().is_some_and(|c| c != '\'') {
            self.at += 1;
        }
        if self.peek().is_none() {
            return Err(LpeError::new(
                column,
                "this label's quote is not closed",
                "close the name with `'`, such as `L'lamp'`",
            ));
        }
        let name: String = self.chars[from..self.at].iter().collect();
        self.at += 1;
        if name.is_empty() {
            return Err(LpeError::new(
                column,
                "the label is empty",
                "name a material or a light between the quotes",
            ));
        }
        Ok((name, column))
    }
}

/// What a letter outside `<>` means: a type (any scattering) or a scattering (any type).
fn letter(c: char) -> Option<(EventType, Scattering)> {
    Some(match c {
        '.' => (EventType::Any, Scattering::Any),
        'C' => (EventType::Camera, Scattering::Any),
        'R' => (EventType::Reflect, Scattering::Any),
        'T' => (EventType::Transmit, Scattering::Any),
        'L' => (EventType::Light, Scattering::Any),
        'O' => (EventType::Object, Scattering::Any),
        'B' => (EventType::Background, Scattering::Any),
        'D' => (EventType::Any, Scattering::Diffuse),
        'G' => (EventType::Any, Scattering::Glossy),
        'S' => (EventType::Any, Scattering::Singular),
        _ => return None,
    })
}

fn unknown_letter(c: char, column: usize) -> LpeError {
    let help = match c {
        'V' => "snell has no volumes, so no volume events (`V`)".to_string(),
        's' => "snell has no straight (`s`) events: thin glass lets light through as `<TS>`".to_string(),
        c if c.is_ascii_lowercase() && letter(c.to_ascii_uppercase()).is_some() => {
            format!("event letters are capitals: `{}`", c.to_ascii_uppercase())
        }
        _ => "events are C (camera), R (reflection), T (transmission), D (diffuse), G (glossy), S (singular), L (light), O (glowing surface), B (background), `.` (any), `<type scattering>` or a 'label'".to_string(),
    };
    LpeError::new(column, format!("`{c}` is not an event"), help)
}

fn unclosed_angle(column: usize) -> LpeError {
    LpeError::new(
        column,
        "this `<` is not closed",
        "close the event with `>`, such as `<RD>`",
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(kind: EventType, scattering: Scattering, column: usize) -> Node {
        Node::Event(EventPattern {
            kind,
            scattering,
            label: None,
            column,
        })
    }

    #[test]
    fn events_sets_groups_and_repeats_parse_with_their_columns() {
        use EventType as E;
        use Scattering as S;
        assert_eq!(
            parse("C<RD>L").unwrap(),
            Node::Seq(vec![
                ev(E::Camera, S::Any, 1),
                ev(E::Reflect, S::Diffuse, 2),
                ev(E::Light, S::Any, 6),
            ])
        );
        assert_eq!(
            parse("C D* L").unwrap(),
            Node::Seq(vec![
                ev(E::Camera, S::Any, 1),
                Node::Repeat {
                    node: Box::new(ev(E::Any, S::Diffuse, 3)),
                    min: 0,
                    max: None
                },
                ev(E::Light, S::Any, 6),
            ])
        );
        let Node::Seq(parts) = parse("C[^D]{1,3}(L|O)").unwrap() else {
            panic!("a sequence")
        };
        assert_eq!(parts.len(), 3);
        assert!(matches!(
            &parts[1],
            Node::Repeat { node, min: 1, max: Some(3) }
                if matches!(**node, Node::Set { negated: true, ref items } if items.len() == 1)
        ));
        assert!(matches!(&parts[2], Node::Alt(a) if a.len() == 2));
        let Node::Seq(parts) = parse("C<T.'glass'>+L'lamp'").unwrap() else {
            panic!("a sequence")
        };
        let Node::Repeat { node, .. } = &parts[1] else {
            panic!("a repeat")
        };
        assert_eq!(
            **node,
            Node::Event(EventPattern {
                kind: E::Transmit,
                scattering: S::Any,
                label: Some(("glass".into(), 5)),
                column: 2
            })
        );
        assert!(
            matches!(&parts[2], Node::Event(e) if e.label == Some(("lamp".into(), 15)) && e.kind == E::Light)
        );
    }

    /// Each mistake is reported at its column, with a hint.
    #[test]
    fn mistakes_point_at_their_column() {
        let cases = [
            ("", 1, "empty"),
            ("C<RD", 2, "not closed"),
            ("C<DR>L", 3, "scattering"),
            ("C<RR>L", 4, "event type"),
            ("C(D|G L", 2, "not closed"),
            ("CD)L", 3, "closes no"),
            ("C(*L)", 3, "repeats"),
            ("*L", 1, "repeats"),
            ("CXL", 2, "not an event"),
            ("CVL", 2, "not an event"),
            ("CdL", 2, "capitals"),
            ("C[]L", 2, "empty"),
            ("C[DL", 2, "not closed"),
            ("C'lampL", 2, "quote"),
            ("CD{3,1}L", 3, "below"),
            ("CD{99}L", 3, "above"),
            ("CD{x}L", 4, "whole number"),
            ("C||L", 3, "expected"),
            ("C<RD'x'Q>L", 8, "unexpected"),
        ];
        for (text, column, words) in cases {
            let e = parse(text).expect_err(text);
            assert_eq!(e.column, column, "{text}: {e:?}");
            assert!(
                e.message.contains(words) || e.help.contains(words),
                "{text}: {e:?}"
            );
            assert!(!e.help.is_empty(), "{text}");
        }
        assert_eq!(cases.len(), 19);
    }
}
