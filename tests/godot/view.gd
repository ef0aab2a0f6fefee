# What the drawing tests share: the windowed godot3 showing `level` over the
# world rectangle $ISOLUX_VIEW ("x,y,w,h"): window and root viewport that
# size, the canvas moved to it, the ambient (CanvasModulate) taken out and
# the background transparent (isolux's map layer leaves what no sprite
# covers transparent). Returns the rectangle.
extends Reference


static func show(tree: SceneTree, level: Node2D) -> Rect2:
	var v = OS.get_environment("ISOLUX_VIEW").split(",")
	var view = Rect2(float(v[0]), float(v[1]), float(v[2]), float(v[3]))
	level.remove_child(level.get_node("Ambient"))
	OS.window_size = view.size
	tree.get_root().size = view.size
	tree.get_root().canvas_transform = Transform2D(0, -view.position)
	tree.get_root().transparent_bg = true
	VisualServer.set_default_clear_color(Color(0, 0, 0, 0))
	tree.get_root().add_child(level)
	return view
