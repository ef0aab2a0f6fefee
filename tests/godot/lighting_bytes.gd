# IsoluxLighting (the GDNative library) inside Godot: opens $ISOLUX_LEVEL (a
# scene JSON or a .tmx), optionally adds a light, renders the default view's
# $ISOLUX_LAYER ("light" or "final") and writes the raw RGBA bytes to
# $ISOLUX_BYTES_OUT; a refusal (a missing file, an integer beyond the C
# API's 32 bits, an unknown layer) must come back as false plus a message.
extends SceneTree


func _init():
	var lighting = load("res://addons/isolux/isolux_lighting.gdns").new()
	if lighting.api_version() != 2:
		printerr("api version ", lighting.api_version())
		quit(1)
		return
	if lighting.open_scene("/nonexistent/level.json") or lighting.last_error().find("level.json") < 0:
		printerr("a missing level is not refused by name: ", lighting.last_error())
		quit(1)
		return
	var level = OS.get_environment("ISOLUX_LEVEL")
	var ok = lighting.open_tmx(level) if level.ends_with(".tmx") else lighting.open_scene(level)
	if not ok:
		printerr("open: ", lighting.last_error())
		quit(1)
		return
	if lighting.set_param("ray_skip", "-1"):
		printerr("ray_skip -1 accepted")
		quit(1)
		return
	# GDScript's 64-bit integers: out of the C API's range, refused by name,
	# never wrapped (4294967396 wraps to 100 in 32 bits); an unknown layer too.
	if not (_refused(lighting, lighting.render(0, 0, 4294967396, 100, 0, "final"), "w = 4294967396")
			and _refused(lighting, lighting.render(0, 0, 64, 64, -1, "final"), "frame = -1")
			and _refused(lighting, lighting.render(5000000000, 0, 64, 64, 0, "final"), "x = 5000000000")
			and _refused(lighting, lighting.render(0, 0, 64, 64, 0, "heat"), "layer \"heat\"")
			and _refused(lighting, lighting.move_light(4294967296, 1.0, 1.0), "id = 4294967296")
			and _refused(lighting, lighting.add_light(1.0, 1.0, 0x1000000), "rgb = 16777216")):
		quit(1)
		return
	var v = lighting.default_view()
	var bytes = lighting.render(int(v.position.x), int(v.position.y), int(v.size.x), int(v.size.y), 0,
		OS.get_environment("ISOLUX_LAYER"))
	if bytes.size() != int(v.size.x * v.size.y * 4):
		printerr("render: ", lighting.last_error())
		quit(1)
		return
	var f = File.new()
	f.open(OS.get_environment("ISOLUX_BYTES_OUT"), File.WRITE)
	f.store_buffer(bytes)
	f.close()
	print("rendered %s: %dx%d" % [level, v.size.x, v.size.y])
	quit(0)


# A call's result is its failure value (false, -1, an empty array) and
# last_error() names `fragment`.
func _refused(lighting, result, fragment: String) -> bool:
	var failed = (typeof(result) == TYPE_BOOL and not result) or (typeof(result) == TYPE_INT and result == -1) \
		or (typeof(result) == TYPE_RAW_ARRAY and result.size() == 0)
	if not failed or lighting.last_error().find(fragment) < 0:
		printerr("not refused by name (", fragment, "): ", lighting.last_error())
		return false
	return true
