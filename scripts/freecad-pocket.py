# Pockets a DXF drawing with FreeCAD's CAM workbench (0.20: Path, Pocket Shape, offset pattern)
# and writes its G-code (GRBL post), for the comparison of issue 18. Run headless:
#   FC_DXF=in.dxf FC_OUT=out.nc FC_TOOL=6 FC_STEPOVER=40 FC_DEPTH=3 freecadcmd scripts/freecad-pocket.py
# The drawing's closed outlines become faces (nested outlines alternate pocket and island); the
# part is a block with those faces sunk FC_DEPTH deep, and one Pocket Shape clears every floor
# in a single step down, climb milling, feeds 1000 / 300 mm/min. Everything else is FreeCAD's
# default.
import os
import sys
import FreeCAD
import Part
import Import
from FreeCAD import Vector

dxf = os.environ["FC_DXF"]
out = os.environ["FC_OUT"]
tool = float(os.environ.get("FC_TOOL", "6"))
stepover = float(os.environ.get("FC_STEPOVER", "40"))
depth = float(os.environ.get("FC_DEPTH", "3"))

doc = FreeCAD.newDocument("pocket")
Import.readDXF(dxf)
doc = FreeCAD.ActiveDocument
edges = [e for o in doc.Objects if hasattr(o, "Shape") for e in o.Shape.Edges]
wires = [Part.Wire(group) for group in Part.sortEdges(edges)]
region = Part.makeFace(wires, "Part::FaceMakerBullseye")
box = region.BoundBox
block = Part.makeBox(box.XLength + 20, box.YLength + 20, depth + 5, Vector(box.XMin - 10, box.YMin - 10, -depth - 5))
sunk = region.translated(Vector(0, 0, -depth)).extrude(Vector(0, 0, depth + 1))
part = doc.addObject("Part::Feature", "Part")
part.Shape = block.cut(sunk).removeSplitter()
for o in list(doc.Objects):
    if o is not part:
        doc.removeObject(o.Name)
doc.recompute()

floors = []
for i, f in enumerate(part.Shape.Faces):
    n = f.normalAt(0, 0)
    if abs(f.CenterOfMass.z + depth) < 1e-6 and n.z > 0.999:
        floors.append("Face%d" % (i + 1))
if not floors:
    sys.exit("no pocket floor found")

from PathScripts import PathJob, PathPocketShape, PathToolController, PathToolBit

job = PathJob.Create("Job", [part])
bit = PathToolBit.Factory.CreateFrom(
    os.path.join(FreeCAD.getResourceDir(), "Mod/Path/Tools/Bit/5mm_Endmill.fctb"), "Endmill"
)
bit.Diameter = tool
tc = PathToolController.Create("TC", bit, 1)
tc.HorizFeed = "1000 mm/min"
tc.VertFeed = "300 mm/min"
tc.SpindleSpeed = 10000
for old in list(job.Tools.Group):
    job.Tools.removeObject(old)
job.Proxy.addToolController(tc)

op = PathPocketShape.Create("Pocket", parentJob=job)
op.Base = [(part, floors)]
op.ToolController = tc
op.OffsetPattern = "Offset"
op.CutMode = "Climb"
op.StepOver = int(round(stepover))
op.StartDepth = 0
op.FinalDepth = -depth
op.StepDown = depth
doc.recompute()

from PathScripts.post import grbl_post

grbl_post.export([tc, op], out, "--no-show-editor")
print("wrote", out, "floors", len(floors), "commands", len(op.Path.Commands))
