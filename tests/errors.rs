//! One error family: every drawing call, from whole meshes down to single triangles and
//! buffer flushes, reports a failing display as `DrawError::Target` (which is a
//! `std::error::Error`, so `?` works in a `main` returning `Box<dyn Error>`).

use embedded_graphics::{pixelcolor::Rgb565, prelude::*};
use zraster::{
    fill_triangle, fill_triangle_shaded, shade::ONE, ColorBuffer, DrawError, ScreenVertex, ZBuffer,
};

/// A display whose bus is down: every call fails with its own error value.
struct Broken;

#[derive(Debug, PartialEq)]
struct BusDown;

impl OriginDimensions for Broken {
    fn size(&self) -> Size {
        Size::new(16, 16)
    }
}

impl DrawTarget for Broken {
    type Color = Rgb565;
    type Error = BusDown;

    fn draw_iter<I: IntoIterator<Item = Pixel<Rgb565>>>(&mut self, _: I) -> Result<(), BusDown> {
        Err(BusDown)
    }
}

fn tri() -> [ScreenVertex; 3] {
    let v = |x, y| ScreenVertex::from_pixels(x, y, 100).unwrap();
    [v(0, 0), v(8, 0), v(0, 8)]
}

#[test]
fn a_failing_display_is_a_target_error_everywhere() {
    let mut depth = [0u16; 16 * 16];
    let mut zbuf = ZBuffer::new(&mut depth, 16, 16).unwrap();
    zbuf.clear();
    let got = fill_triangle(&mut Broken, &mut zbuf, &tri(), Rgb565::RED);
    assert_eq!(got, Err(DrawError::Target(BusDown)));
    zbuf.clear();
    let red = embedded_graphics::pixelcolor::Rgb888::RED;
    let got = fill_triangle_shaded(&mut Broken, &mut zbuf, &tri(), red, [ONE; 3]);
    assert_eq!(got, Err(DrawError::Target(BusDown)));

    let mut pixels = [Rgb565::BLACK; 16 * 16];
    let frame = ColorBuffer::new(&mut pixels, 16, 16).unwrap();
    assert_eq!(frame.flush(&mut Broken), Err(DrawError::Target(BusDown)));
}

#[test]
fn draw_errors_box_into_std_errors() {
    fn run() -> Result<(), Box<dyn std::error::Error>> {
        let mut pixels = [Rgb565::BLACK; 4];
        ColorBuffer::new(&mut pixels, 2, 2)?.flush(&mut Broken)?;
        Ok(())
    }
    let e = run().unwrap_err();
    assert!(e.to_string().contains("BusDown"), "{e}");
}
