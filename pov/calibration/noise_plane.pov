// Calibration render of POV-Ray's noise (pov/calibration/calibrate.sh runs it; see docs/pov.md).
//
// Renders the raw value of f_noise_generator(…, 2) — the noise every procedural stochtex include
// builds its octaves from — on a plane slice, as the include does: the solid noise rotated by
// Angles and moved by Offset, one lattice cell per 8 pixels, no anti-aliasing. The output is
// linear (EXR, no colour management), so the core's metrics measure the noise itself.
//   povray -D +W1024 +H1024 -A +FE noise_plane.pov Declare=AngleX=… Declare=AngleY=… …
#version 3.7;
global_settings { assumed_gamma 1.0 }

#ifndef (AngleX) #declare AngleX = 0; #end
#ifndef (AngleY) #declare AngleY = 0; #end
#ifndef (AngleZ) #declare AngleZ = 0; #end
#ifndef (Offset) #declare Offset = 1000.5; #end
#ifndef (Cells) #declare Cells = 128; #end  // lattice cells across the image

#declare Calibration_Noise = function { internal(78) }  // f_noise_generator (functions.inc)
#declare Angles = <AngleX, AngleY, AngleZ>;
#declare Cx = vrotate(x, Angles);
#declare Cy = vrotate(y, Angles);
#declare Cz = vrotate(z, Angles);
#declare R11 = Cx.x; #declare R12 = Cy.x; #declare R13 = Cz.x;
#declare R21 = Cx.y; #declare R22 = Cy.y; #declare R23 = Cz.y;
#declare R31 = Cx.z; #declare R32 = Cy.z; #declare R33 = Cz.z;
#declare Value = function {
  Calibration_Noise(R11*x + R12*y + R13*z + Offset, R21*x + R22*y + R23*z + Offset, R31*x + R32*y + R33*z + Offset, 2)
}

camera { orthographic location <0.5*Cells, 0.5*Cells, -1> direction z right Cells*x up Cells*y }
plane {
  z, 0
  // Function patterns wrap values outside [0, 1]; this noise stays inside (measured: 0.06–0.96).
  pigment { function { min(1, max(0, Value(x, y, z))) } color_map { [0 rgb 0] [1 rgb 1] } }
  finish { emission 1 diffuse 0 ambient 0 }
}
