//! `sin` and `cos` of one angle with a single range reduction (the FK hot path evaluates both
//! for every joint; `f64::sin_cos` calls libm twice).
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

#[cfg(test)]
mod tests {
    use super::sin_cos;

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
