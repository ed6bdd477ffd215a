// Showcase: one texture, both include modes, on objects with sharp edges under ordinary
// lighting. The cube, the columns and the sphere use the procedural (solid) include; the floor
// uses the baked one. Generated images: docs/images/pov-showcase.png; see docs/pov.md.
//
//   stex analyze data/exemplars/concrete_512.png -o out/pov/concrete.stex
//   stex pov out/pov/concrete.stex -o out/pov/showcase_procedural.inc --name Showcase_Procedural
//   stex pov out/pov/concrete.stex -o out/pov/showcase_baked.inc --name Showcase_Baked --mode baked \
//            --bake-size 2048
//   povray -D +W800 +H450 +A0.1 +AM2 +R2 +Lout/pov +Iscenes/pov/showcase.pov +Oout/pov/showcase.png
//
// Any texture works: the scene only assumes a photo about 1 m wide (the texture unit).
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 }

// The texture unit is the photo's width; the objects are about 1 m, so show a few widths.
#declare Showcase_Procedural_Scale = 1;
#declare Showcase_Baked_Scale = 1;
#include "showcase_procedural.inc"
#include "showcase_baked.inc"

camera {
  perspective
  location <3.4, 1.9, -5.6>
  look_at <0.1, 0.85, 0.6>
  right x * image_width / image_height
  angle 48
}

// Key light (sun-like, warm) with shadows, a cool shadowless fill, and a pale sky.
light_source { <30, 45, -25> * 100 color rgb <1.0, 0.96, 0.9> * 1.6 }  // far: parallel rays
light_source { <-20, 15, -30> color rgb <0.75, 0.82, 1.0> * 0.45 shadowless }
sky_sphere {
  pigment { gradient y color_map { [0 color rgb <0.85, 0.88, 0.92>] [1 color rgb <0.35, 0.5, 0.75>] } }
}

// Floor (baked include: box mapping projects the image along y onto it). A 2048² bake repeats
// every 4 texture units (4 m here): less visible than 1 m on a floor that reaches the horizon.
plane { y, 0 texture { Showcase_Baked } }

// A cube with sharp edges, turned to show three faces.
box { <-0.6, 0, -0.6>, <0.6, 1.2, 0.6> texture { Showcase_Procedural } rotate 25 * y translate <-0.9, 0, 0.4> }

// Columns: cylinders on square plinths.
#macro Column(Position, Height)
  union {
    box { <-0.28, 0, -0.28>, <0.28, 0.18, 0.28> }
    cylinder { <0, 0.18, 0>, <0, Height - 0.18, 0>, 0.2 }
    box { <-0.28, Height - 0.18, -0.28>, <0.28, Height, 0.28> }
    texture { Showcase_Procedural }
    translate Position
  }
#end
Column(<1.3, 0, 1.6>, 1.9)
Column(<-1.9, 0, 2.4>, 1.9)
Column(<2.6, 0, 3.6>, 1.9)

// A sphere resting on the floor.
sphere { <0.85, 0.55, -0.7>, 0.55 texture { Showcase_Procedural } }
