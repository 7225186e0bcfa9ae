//! Validation messages shared by every layer that checks user input.
//!
//! A [`Violation`] names the key, the value and the rule, so that a message reads
//! `friction.mu_k = 0.5 must be less than friction.mu_s = 0.4`.

use std::fmt;

/// One broken rule of a case or an argument.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    /// Dotted key, e.g. `friction.mu_k`.
    pub key: String,
    /// The offending value as the user wrote it (or as parsed).
    pub value: String,
    /// What is allowed, phrased to follow `key = value`.
    pub rule: String,
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {} {}", self.key, self.value, self.rule)
    }
}

/// Collects violations under a key prefix (`friction`, `scene`, ...).
#[derive(Debug)]
pub struct Checker<'a> {
    prefix: &'a str,
    pub violations: Vec<Violation>,
}

impl<'a> Checker<'a> {
    pub fn new(prefix: &'a str) -> Self {
        Self { prefix, violations: Vec::new() }
    }

    /// The full dotted name of `key` under this checker's prefix.
    pub fn key(&self, key: &str) -> String {
        if self.prefix.is_empty() { key.to_string() } else { format!("{}.{}", self.prefix, key) }
    }

    /// Records a violation of `key` with a free-form rule.
    pub fn fail(&mut self, key: &str, value: impl ValueText, rule: impl Into<String>) {
        let key = self.key(key);
        self.violations.push(Violation { key, value: value.text(), rule: rule.into() });
    }

    /// `value` must be a finite number.
    pub fn finite(&mut self, key: &str, value: f64) -> bool {
        if value.is_finite() {
            true
        } else {
            self.fail(key, value, "must be a finite number");
            false
        }
    }

    /// `value` must be finite and `> 0`.
    pub fn positive(&mut self, key: &str, value: f64) {
        if self.finite(key, value) && value <= 0.0 {
            self.fail(key, value, "must be greater than 0");
        }
    }

    /// `value` must be finite and `≥ 0`.
    pub fn non_negative(&mut self, key: &str, value: f64) {
        if self.finite(key, value) && value < 0.0 {
            self.fail(key, value, "must be greater than or equal to 0");
        }
    }

    /// Merges the violations of a nested checker.
    pub fn absorb(&mut self, other: Checker<'_>) {
        self.violations.extend(other.violations);
    }
}

/// A number as a person reads it: plain up to eight characters (`0.5`, `1000`, `400.0001`),
/// else whichever of the plain and the exponent form is shorter (`1e-7`, `1e-320`, `1e300`,
/// not dozens or hundreds of digits). Both forms read back to the same `f64`.
pub fn shortest(x: f64) -> String {
    let plain = x.to_string();
    let exponent = format!("{x:e}");
    if plain.len() <= 8 || plain.len() <= exponent.len() { plain } else { exponent }
}

/// How a value is written in a [`Violation`]: numbers in their [`shortest`] form.
pub trait ValueText {
    fn text(&self) -> String;
}

impl ValueText for f64 {
    fn text(&self) -> String {
        shortest(*self)
    }
}

macro_rules! value_text_as_display {
    ($($t:ty),*) => {$(
        impl ValueText for $t {
            fn text(&self) -> String {
                self.to_string()
            }
        }
    )*};
}

value_text_as_display!(i32, i64, u32, u64, usize, &str, String);
