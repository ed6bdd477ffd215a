// A height map lit by one directional light, seen from straight above: the POV-Ray twin of
// stochtex's relief test data (core/include/stochtex/models/relief_shading.h; docs/models/ptm.md,
// "Test data"). tests/ptm_scene_test.cpp renders it and compares it with the C++ renderer.
//
// Declare on the command line (Declare=NAME=VALUE):
//   Size     texels per side of the height map (the image is Size × Size pixels, one per texel)
//   Depth    height range in texels (the map's 0 … 1)
//   Light_X, Light_Y, Light_Z  unit light direction: x to the image's right, y to its top,
//            z out of the surface
// and pass the map as +L folder with file name "relief_height.png" (16-bit grey).
//
// Model: albedo · max(0, n·l) with cast shadows: finish ambient 0, diffuse 1, no specular; a
// parallel light of intensity 1; the albedo the same function of height as the C++ surface
// (dark brown hollows, light grey ridges: smoothstep between heights 0.35 and 0.8).
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 2 }

// The height field's vertex (i, j) sits at x = i, z = Size − 1 − j (image rows go down, z goes
// up the image), y = height: POV-Ray's y is the surface's z, its z the image's y.
camera {
    // Explicit vectors, no look_at: looking straight down −y the sky vector is degenerate, and
    // these keep +x to the right and +z (the image's y) up.
    orthographic
    location <(Size - 1) / 2, Depth + 10, (Size - 1) / 2>
    direction -y
    right x * Size
    up z * Size
}
light_source { <Light_X, Light_Z, Light_Y> * 1000 color rgb 1 parallel point_at <0, 0, 0> }

#declare Hollow = rgb <0.30, 0.21, 0.14>;
#declare Ridge = rgb <0.62, 0.60, 0.56>;
#macro Smooth_Colour(T) (Hollow + (Ridge - Hollow) * T * T * (3 - 2 * T)) #end
height_field {
    png "relief_height.png"
    smooth
    pigment {
        gradient y
        color_map {
            [0.00 Hollow] [0.35 Hollow]
            #for (K, 1, 9) [0.35 + 0.45 * K / 10 Smooth_Colour(K / 10)] #end
            [0.80 Ridge] [1.00 Ridge]
        }
        scale <1, 1.001, 1>  // the pattern repeats at y = 1: keep the highest point in the first period
    }
    finish { ambient 0 emission 0 diffuse 1 specular 0 phong 0 }
    scale <Size - 1, Depth, Size - 1>
}
