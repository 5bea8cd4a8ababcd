// The headset protocol v1 (unity-bridge/protocol/v1/*.schema.json) as plain C# classes, field for
// field: an Envelope carries one body; each body class names its JSON fields exactly as the schema
// does and writes optional fields only when they are set. No UnityEngine here, so the same classes
// compile under mono for the protocol round-trip test (tests/test_unity_package.py).
using System;
using System.Collections.Generic;
using System.Globalization;

namespace H3ds.Bridge.Protocol
{
    /// <summary>A message that does not follow the protocol; the text names the field.</summary>
    public sealed class ProtocolException : Exception
    {
        public ProtocolException(string message) : base(message) { }
    }

    public static class MessageTypes
    {
        public const int Version = 1;
        public const string Hello = "hello", Pair = "pair", Paired = "paired", ScenePush = "scene_push",
            SceneLoaded = "scene_loaded", SceneFailed = "scene_failed", PlanStepResult = "plan_step_result",
            GloveEvent = "glove_event", UserDecision = "user_decision", Ping = "ping", Pong = "pong",
            Ack = "ack", Error = "error", SessionEnd = "session_end";
    }

    /// <summary>The envelope every message has: version, type, session, id, seq, ts, body.</summary>
    public sealed class Envelope
    {
        public int Version = MessageTypes.Version;
        public string Type;
        public string Session;
        public string Id;
        public long Seq;
        public double Ts;
        public Dictionary<string, object> Body = new Dictionary<string, object>();

        public string ToJson()
        {
            var o = new Dictionary<string, object>();
            o["version"] = (long)Version;
            o["type"] = Type;
            o["session"] = Session;
            o["id"] = Id;
            o["seq"] = Seq;
            o["ts"] = Ts;
            o["body"] = Body;
            return Json.Write(o);
        }

        public static Envelope FromJson(string text)
        {
            object parsed;
            try { parsed = Json.Parse(text); }
            catch (FormatException e) { throw new ProtocolException("malformed: " + e.Message); }
            var o = parsed as Dictionary<string, object>;
            if (o == null) throw new ProtocolException("a message must be a JSON object");
            var env = new Envelope();
            env.Version = (int)Fields.Long(o, "version");
            if (env.Version != MessageTypes.Version)
                throw new ProtocolException("version " + env.Version + " is not supported (this headset speaks " + MessageTypes.Version + ")");
            env.Type = Fields.String(o, "type");
            env.Session = Fields.String(o, "session");
            env.Id = Fields.String(o, "id");
            env.Seq = Fields.Long(o, "seq");
            env.Ts = Fields.Double(o, "ts");
            env.Body = Fields.Dict(o, "body");
            return env;
        }
    }

    /// <summary>Typed access to a parsed JSON object; a missing or mistyped field throws ProtocolException.</summary>
    public static class Fields
    {
        public static bool Has(Dictionary<string, object> o, string key) { return o.ContainsKey(key) && o[key] != null; }

        static object Get(Dictionary<string, object> o, string key)
        {
            object v;
            if (!o.TryGetValue(key, out v) || v == null) throw new ProtocolException("field '" + key + "' is missing");
            return v;
        }

        public static string String(Dictionary<string, object> o, string key)
        {
            var s = Get(o, key) as string;
            if (s == null) throw new ProtocolException("field '" + key + "' must be a string");
            return s;
        }

        public static string OptString(Dictionary<string, object> o, string key) { return Has(o, key) ? String(o, key) : null; }

        public static long Long(Dictionary<string, object> o, string key)
        {
            var v = Get(o, key);
            if (v is long) return (long)v;
            if (v is double && Math.Floor((double)v) == (double)v) return (long)(double)v;
            throw new ProtocolException("field '" + key + "' must be an integer");
        }

        public static double Double(Dictionary<string, object> o, string key)
        {
            var v = Get(o, key);
            if (v is long) return (long)v;
            if (v is double) return (double)v;
            throw new ProtocolException("field '" + key + "' must be a number");
        }

        public static bool Bool(Dictionary<string, object> o, string key)
        {
            var v = Get(o, key);
            if (!(v is bool)) throw new ProtocolException("field '" + key + "' must be true or false");
            return (bool)v;
        }

        public static Dictionary<string, object> Dict(Dictionary<string, object> o, string key)
        {
            var d = Get(o, key) as Dictionary<string, object>;
            if (d == null) throw new ProtocolException("field '" + key + "' must be an object");
            return d;
        }

        public static List<object> List(Dictionary<string, object> o, string key)
        {
            var l = Get(o, key) as List<object>;
            if (l == null) throw new ProtocolException("field '" + key + "' must be an array");
            return l;
        }

        public static double AsDouble(object v, string what)
        {
            if (v is long) return (long)v;
            if (v is double) return (double)v;
            throw new ProtocolException(what + " must be a number");
        }
    }

    /// <summary>A message body: the type it belongs to and its JSON fields.</summary>
    public interface IBody
    {
        string Type { get; }
        Dictionary<string, object> ToBody();
    }

    public sealed class GloveState
    {
        public bool Left, Right;
    }

    /// <summary>hello (both ways). The studio's reply adds max_message_bytes.</summary>
    public sealed class Hello : IBody
    {
        public string Role = "headset";
        public string Device;
        public string AppVersion;
        public List<string> Capabilities = new List<string>();
        public GloveState Gloves;
        public long? MaxMessageBytes;
        public string Type { get { return MessageTypes.Hello; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object>();
            b["role"] = Role;
            b["device"] = Device;
            if (AppVersion != null) b["app_version"] = AppVersion;
            if (Capabilities != null) b["capabilities"] = Capabilities;
            if (Gloves != null)
                b["gloves"] = new Dictionary<string, object> { { "left", Gloves.Left }, { "right", Gloves.Right } };
            if (MaxMessageBytes.HasValue) b["max_message_bytes"] = MaxMessageBytes.Value;
            return b;
        }

        public static Hello FromBody(Dictionary<string, object> b)
        {
            var h = new Hello { Role = Fields.String(b, "role"), Device = Fields.String(b, "device"), AppVersion = Fields.OptString(b, "app_version") };
            if (Fields.Has(b, "capabilities"))
            {
                h.Capabilities = new List<string>();
                foreach (var c in Fields.List(b, "capabilities")) h.Capabilities.Add(c as string);
            }
            if (Fields.Has(b, "gloves"))
            {
                var g = Fields.Dict(b, "gloves");
                h.Gloves = new GloveState { Left = Fields.Bool(g, "left"), Right = Fields.Bool(g, "right") };
            }
            if (Fields.Has(b, "max_message_bytes")) h.MaxMessageBytes = Fields.Long(b, "max_message_bytes");
            return h;
        }
    }

    /// <summary>pair: the 6-digit token shown in the studio, or the resume key after a reconnect.</summary>
    public sealed class Pair : IBody
    {
        public string Token;
        public string ResumeKey;
        public string Type { get { return MessageTypes.Pair; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object>();
            if (Token != null) b["token"] = Token;
            if (ResumeKey != null) b["resume_key"] = ResumeKey;
            return b;
        }
    }

    public sealed class Paired
    {
        public string HeadsetId, ResumeKey, Studio;
        public long LastSeq;

        public static Paired FromBody(Dictionary<string, object> b)
        {
            return new Paired
            {
                HeadsetId = Fields.String(b, "headset_id"),
                ResumeKey = Fields.String(b, "resume_key"),
                Studio = Fields.String(b, "studio"),
                LastSeq = Fields.Long(b, "last_seq"),
            };
        }
    }

    public sealed class SceneLoaded : IBody
    {
        public string Push;
        public double? LoadMs;
        public long? Objects;
        public string Type { get { return MessageTypes.SceneLoaded; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object> { { "push", Push } };
            if (LoadMs.HasValue) b["load_ms"] = LoadMs.Value;
            if (Objects.HasValue) b["objects"] = Objects.Value;
            return b;
        }
    }

    public sealed class SceneFailed : IBody
    {
        public string Push, Reason;
        public string Type { get { return MessageTypes.SceneFailed; } }
        public Dictionary<string, object> ToBody() { return new Dictionary<string, object> { { "push", Push }, { "reason", Reason } }; }
    }

    public sealed class PlanStepResult : IBody
    {
        public string Push;
        public long Index, Of;
        public string Action;
        public bool Ok;
        public string Message;
        public string Type { get { return MessageTypes.PlanStepResult; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object> { { "push", Push }, { "index", Index }, { "of", Of }, { "action", Action }, { "ok", Ok } };
            if (Message != null) b["message"] = Message;
            return b;
        }
    }

    public sealed class GloveEvent : IBody
    {
        public string Push;
        public double T;
        public string ObjectId, ObjectType;
        public string Kind;   // hover | unhover | select | unselect
        public string Hand;   // left | right
        public List<string> Fingers = new List<string>();  // thumb index middle ring little palm
        public string HapticClass;  // hot | cold | light | normal
        public long Intensity;      // 0-100
        public double[] GloveColour = new double[3];  // linear RGB 0-1
        public string Type { get { return MessageTypes.GloveEvent; } }

        public Dictionary<string, object> ToBody()
        {
            return new Dictionary<string, object>
            {
                { "push", Push }, { "t", T }, { "object_id", ObjectId }, { "object_type", ObjectType },
                { "kind", Kind }, { "hand", Hand }, { "fingers", Fingers }, { "haptic_class", HapticClass },
                { "intensity", Intensity },
                { "glove_colour", new List<object> { GloveColour[0], GloveColour[1], GloveColour[2] } },
            };
        }
    }

    public sealed class UserDecision : IBody
    {
        public string Push, Decision, Comment;  // decision: accept | reject
        public string Type { get { return MessageTypes.UserDecision; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object> { { "push", Push }, { "decision", Decision } };
            if (Comment != null) b["comment"] = Comment;
            return b;
        }
    }

    public sealed class Ping : IBody
    {
        public string Type { get { return MessageTypes.Ping; } }
        public Dictionary<string, object> ToBody() { return new Dictionary<string, object>(); }
    }

    public sealed class Pong : IBody
    {
        public string PingId;
        public string Type { get { return MessageTypes.Pong; } }
        public Dictionary<string, object> ToBody() { return new Dictionary<string, object> { { "ping", PingId } }; }
    }

    public sealed class Ack : IBody
    {
        public string Of;
        public long Seq;
        public bool? Duplicate;
        public string Type { get { return MessageTypes.Ack; } }

        public Dictionary<string, object> ToBody()
        {
            var b = new Dictionary<string, object> { { "of", Of }, { "seq", Seq } };
            if (Duplicate.HasValue) b["duplicate"] = Duplicate.Value;
            return b;
        }

        public static Ack FromBody(Dictionary<string, object> b)
        {
            var a = new Ack { Of = Fields.String(b, "of"), Seq = Fields.Long(b, "seq") };
            if (Fields.Has(b, "duplicate")) a.Duplicate = Fields.Bool(b, "duplicate");
            return a;
        }
    }

    public sealed class ErrorMessage
    {
        public string Code, Message, Of;
        public bool Fatal;

        public static ErrorMessage FromBody(Dictionary<string, object> b)
        {
            return new ErrorMessage
            {
                Code = Fields.String(b, "code"),
                Message = Fields.String(b, "message"),
                Of = Fields.OptString(b, "of"),
                Fatal = Fields.Has(b, "fatal") && Fields.Bool(b, "fatal"),
            };
        }
    }

    public sealed class SessionEnd : IBody
    {
        public string Reason;
        public string Type { get { return MessageTypes.SessionEnd; } }
        public Dictionary<string, object> ToBody() { return new Dictionary<string, object> { { "reason", Reason } }; }
    }
}
