// The headset's send side: numbers every message (seq +1 from 1, never reset, also across reconnects;
// hello, pair, ack, pong and error are never resent and carry seq 0),
// keeps every message the studio must acknowledge until its ack arrives, and hands back the unacked
// ones in seq order, unchanged (same id, seq, ts), to resend after a reconnect. The studio
// de-duplicates by (session, seq), so resending one that was stored already is harmless.
using System;
using System.Collections.Generic;

namespace H3ds.Bridge.Protocol
{
    public sealed class Outbox
    {
        readonly SortedDictionary<long, Envelope> _unacked = new SortedDictionary<long, Envelope>();
        readonly Func<double> _clock;
        readonly int _capacity;
        long _seq;

        public string Session { get; private set; }
        /// <summary>Messages dropped because the buffer was full while disconnected (oldest first).</summary>
        public long Dropped { get; private set; }
        public int Pending { get { return _unacked.Count; } }
        public long LastSeq { get { return _seq; } }

        public Outbox(string session, Func<double> clock, int capacity = 100000, long lastSeq = 0)
        {
            if (string.IsNullOrEmpty(session) || session.Length > 64) throw new ArgumentException("session must be 1-64 characters");
            Session = session;
            _clock = clock;
            _capacity = capacity;
            _seq = lastSeq;
        }

        /// <summary>Types the studio acknowledges; only these are kept for resending.</summary>
        public static bool NeedsAck(string type)
        {
            return type != MessageTypes.Hello && type != MessageTypes.Pair && type != MessageTypes.Ping
                && type != MessageTypes.Pong && type != MessageTypes.Ack && type != MessageTypes.Error;
        }

        /// <summary>Types that carry seq 0: answers and handshakes, never stored or resent.</summary>
        public static bool Unnumbered(string type)
        {
            return type == MessageTypes.Hello || type == MessageTypes.Pair || type == MessageTypes.Ack
                || type == MessageTypes.Pong || type == MessageTypes.Error;
        }

        /// <summary>Wraps a body in a new envelope (next seq, a fresh id, now) and keeps it if it needs an ack.</summary>
        public Envelope Next(IBody body)
        {
            var env = new Envelope
            {
                Type = body.Type, Session = Session, Id = Guid.NewGuid().ToString(), Seq = Unnumbered(body.Type) ? 0 : ++_seq,
                Ts = _clock(), Body = body.ToBody(),
            };
            if (NeedsAck(env.Type))
            {
                if (_unacked.Count >= _capacity)
                {
                    using (var e = _unacked.Keys.GetEnumerator()) { e.MoveNext(); _unacked.Remove(e.Current); }
                    Dropped++;
                }
                _unacked[env.Seq] = env;
            }
            return env;
        }

        /// <summary>The studio stored (or had stored) the message with this seq.</summary>
        public bool Acknowledge(long seq) { return _unacked.Remove(seq); }

        /// <summary>After pairing: everything up to the studio's last stored seq is safe.</summary>
        public void StoredUpTo(long lastSeq)
        {
            var done = new List<long>();
            foreach (var s in _unacked.Keys) { if (s <= lastSeq) done.Add(s); else break; }
            foreach (var s in done) _unacked.Remove(s);
            if (lastSeq > _seq) _seq = lastSeq;
        }

        /// <summary>The unacked messages in seq order, to resend unchanged.</summary>
        public List<Envelope> Unacked() { return new List<Envelope>(_unacked.Values); }
    }
}
