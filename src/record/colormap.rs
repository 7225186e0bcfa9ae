//! Colour scales for series (by position along the surface) and slip rate.

/// Blue → green → yellow (viridis stops): series coloured by position from the left.
pub const POSITION: [[u8; 3]; 5] = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];

/// Black → purple → red → yellow (inferno stops): slip rate.
pub const SLIP_RATE: [[u8; 3]; 6] =
    [[0, 0, 4], [66, 10, 104], [147, 38, 103], [221, 81, 58], [252, 165, 10], [252, 255, 164]];

/// The colour at `t ∈ [0, 1]` (clamped), linear between equally spaced stops.
pub fn sample(stops: &[[u8; 3]], t: f64) -> [u8; 3] {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let w = x - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + w * (b as f64 - a as f64)).round() as u8;
    [mix(stops[i][0], stops[i + 1][0]), mix(stops[i][1], stops[i + 1][1]), mix(stops[i][2], stops[i + 1][2])]
}
