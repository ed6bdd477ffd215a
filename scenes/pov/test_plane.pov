// Measurement scene: a flat plane seen by an orthographic camera, lit by nothing but its own
// texture (emission 1), so each pixel is the texture's value at its centre — what `stex render`
// computes for the same region. Used by tests/pov_scene_test.cpp; see docs/pov.md.
//
//   stex pov T.stex -o DIR/plane_texture.inc --name Plane_Texture [--mode baked]
//   povray -D -A +FE +W512 +H512 +LDIR +Iscenes/pov/test_plane.pov +ODIR/plane.exr \
//          Declare=Extent_U=1 Declare=Extent_V=1 Declare=Depth=0.25
//
// The image covers texture coordinates u in [0, Extent_U] (left to right) and v in
// [0, Extent_V] (top to bottom) on the solid texture's slice w = Depth, i.e. `stex render
// --size 512x512 --scale S [--solid --z Depth]` with S = Extent_U · pixels_per_unit / 512.
// +FE writes linear EXR: neither gamma-encoded nor clamped to [0, 1].
#version 3.7;
global_settings { assumed_gamma 1.0 }

#ifndef (Extent_U) #declare Extent_U = 1; #end
#ifndef (Extent_V) #declare Extent_V = Extent_U; #end
#ifndef (Depth) #declare Depth = 0; #end

#declare Plane_Texture_Scale = 1;  // one POV-Ray unit per texture unit
#include "plane_texture.inc"

// Texture space has v along -y (image rows go down): the view is the quadrant y ≤ 0.
camera {
  orthographic
  location <Extent_U / 2, -Extent_V / 2, Depth - 1>
  direction z
  right Extent_U * x
  up Extent_V * y
}
plane {
  z, Depth
  texture { pigment { Plane_Texture_Pigment } finish { emission 1 diffuse 0 ambient 0 } }
}
