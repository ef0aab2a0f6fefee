# isolux's own lighting inside Godot: a light walks a loop through the level
# and IsoluxLighting (libisolux, GDNative) renders every frame, shadows from
# the solids it estimates from the sprites included. The picture is a Sprite's
# texture; a game would draw its characters over it.
#
# For tests: ISOLUX_DEMO_FRAMES=N quits after N frames, writing the last
# one's RGBA bytes to $ISOLUX_DEMO_OUT and the walking light's position and
# the view to $ISOLUX_DEMO_OUT.txt.
extends Node2D

const LEVEL := "res://demo/level.json"
const WALKER_COLOUR := 0xffe0b0
const WALKER_HEIGHT := 30.0

var lighting = null
var walker := -1
var view := Rect2()
var frame := 0
var texture := ImageTexture.new()


func _ready():
	lighting = load("res://addons/isolux/isolux_lighting.gdns").new()
	if not lighting.open_scene(ProjectSettings.globalize_path(LEVEL)):
		push_error("isolux: " + lighting.last_error())
		get_tree().quit(1)
		return
	view = lighting.default_view()
	walker = lighting.add_light(0, 0, WALKER_COLOUR, WALKER_HEIGHT)
	$Picture.texture = texture


# A loop around the view's centre, in whole pixels.
func walker_at(f: int) -> Vector2:
	var t := f * 0.03
	var c := view.position + view.size / 2
	return Vector2(round(c.x + cos(t) * view.size.x * 0.3), round(c.y + sin(t) * view.size.y * 0.3))


func _process(_delta):
	if walker < 0:
		return
	var at := walker_at(frame)
	lighting.move_light(walker, at.x, at.y)
	var bytes = lighting.render(int(view.position.x), int(view.position.y), int(view.size.x), int(view.size.y),
		frame, "final")
	if bytes.size() == 0:
		push_error("isolux: " + lighting.last_error())
		get_tree().quit(1)
		return
	var img := Image.new()
	img.create_from_data(int(view.size.x), int(view.size.y), false, Image.FORMAT_RGBA8, bytes)
	texture.create_from_image(img, 0)
	frame += 1
	var frames := int(OS.get_environment("ISOLUX_DEMO_FRAMES"))
	if frames > 0 and frame >= frames:
		var out := OS.get_environment("ISOLUX_DEMO_OUT")
		var f := File.new()
		f.open(out, File.WRITE)
		f.store_buffer(bytes)
		f.close()
		f.open(out + ".txt", File.WRITE)
		f.store_string("%d %d %d %d %d %d %d\n" % [frame - 1, at.x, at.y, view.position.x, view.position.y,
			view.size.x, view.size.y])
		f.close()
		get_tree().quit(0)
